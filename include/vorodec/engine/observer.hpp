#pragma once
// What samples a run: an output observes the state when the driver says so (driver.hpp). Outputs
// implement Observer (src/outputs); drivers only call Observers::sample.
#include <memory>
#include <vector>

#include "vorodec/checkpoint/archive.hpp"
#include "vorodec/engine/driver.hpp"

namespace vorodec::run {

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

}  // namespace vorodec::run
