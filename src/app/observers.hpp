#pragma once
// The observers of a run: history.csv, the crack catalogue (cracks.csv, rows appended as cracks
// occur), the VTK series with rose.csv, the acoustic-emission events. Each writes whole rows and
// whole files, so a killed run leaves files that parse; each saves where its files stand for a
// checkpoint and continues them from there when the run resumes.
#include <filesystem>
#include <memory>
#include <vector>

#include "damage_output.hpp"
#include "driver.hpp"
#include "vorodec/io/csv_writer.hpp"
#include "vorodec/io/model_file.hpp"
#include "vorodec/measure/ae_catalogue.hpp"
#include "vorodec/measure/cycles.hpp"

namespace vorodec::app {

class Observer {
 public:
  virtual ~Observer() = default;
  virtual void sample(const RunView&, const Sample&) {}
  // After every advance of the driver.
  virtual void after_advance(const RunView&) {}
  // Everything sampled so far reaches the files.
  virtual void flush() = 0;
  // After flush(): where the files stand and what the observer has gathered.
  virtual void save(checkpoint::OutArchive& ar) const = 0;
};

class Observers {
 public:
  void add(std::unique_ptr<Observer> o) { list_.push_back(std::move(o)); }
  void sample(const RunView& v, const Sample& s) {
    for (auto& o : list_) o->sample(v, s);
  }
  void after_advance(const RunView& v) {
    for (auto& o : list_) o->after_advance(v);
  }
  void flush() {
    for (auto& o : list_) o->flush();
  }
  void save(checkpoint::OutArchive& ar) const {
    for (const auto& o : list_) o->save(ar);
  }

 private:
  std::vector<std::unique_ptr<Observer>> list_;
};

// The specimen's stress-strain curve as the summary fits it, gathered from the history rows.
struct Curve {
  std::vector<double> strain, stress, lateral, failure_rate;
  std::vector<measure::HistoryPoint> rows;
};

// The observers of a quasi-static run, fresh (resume == nullptr) or continued from a checkpoint
// whose archive stands at their state. `curve` is filled by the history observer.
Observers make_observers(const RunView& view, const DamageOutput& damage,
                         const measure::AeSettings& ae, const std::filesystem::path& out,
                         bool write_vtk, Curve& curve, checkpoint::InArchive* resume);

}  // namespace vorodec::app
