#pragma once
// A stage mode: what a kind of quasi-static stage does beyond its platen control (creep: a
// density-scaled creep step and creep failure; corrosion: the bonds' static fatigue). One object
// per run for each mode its stages use, made by its row in stage_modes.cpp. It brings its
// model-file keys (io::StageModeKeys), its history columns, its progress text, its summary.json
// section and its checkpoint state, so neither the model-file reader nor the driver knows them.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/io/json.hpp"
#include "vorodec/measure/specimen.hpp"

namespace vorodec::run {

// The stage a mode runs, as the driver sees it.
struct StageContext {
  const loading::Stage& stage;
  std::size_t index;  // in the load path
  double t0;          // s, the stage's start time
};

// What a mode asks for after a step of its stage.
struct ModeVerdict {
  std::string sample;  // a history row labelled stage name + this (empty: none)
  std::string status;  // the run's status from now on (empty: unchanged)
  bool end_stage = false;
  bool stop_run = false;  // after this stage, whatever follows
};

class StageMode {
 public:
  virtual ~StageMode() = default;
  // Whether `stage` is one of this mode's (its control is the mode's).
  bool runs(const loading::Stage& stage) const { return stage.mode == control_; }
  // The stage starts (the driver restores the model file's time step after unless this is true).
  virtual void begin_stage(const StageContext& c) = 0;
  virtual bool sets_time_step() const { return false; }
  virtual ModeVerdict after_step(const StageContext& c, const measure::SpecimenState& s) = 0;
  // The run went unstable in the stage: the run's status (empty: the driver's own).
  virtual std::string unstable(const StageContext& c, const std::string& what) = 0;
  virtual void end_stage(const StageContext& c) = 0;
  // The progress line: a clock, what the stage waits for; true when nothing else applies.
  virtual bool progress(const StageContext& c, ProgressReport& r) const = 0;
  // history.csv: its columns' names, and their values now (appended in that order).
  virtual std::vector<std::string> column_names() const = 0;
  virtual void column_values(std::vector<double>& row) const = 0;
  // summary.json: its section, if its stages ran.
  virtual void summarise(io::Json& summary) const = 0;
  // Checkpoints: its state; `current` is the stage the driver stands at when loading.
  virtual void save(checkpoint::OutArchive& ar) const = 0;
  virtual void load(checkpoint::InArchive& ar, const loading::Stage& current) = 0;

 private:
  friend std::vector<std::unique_ptr<StageMode>> make_stage_modes(const DriverContext& c);
  std::string control_;  // the row's io::StageModeKeys::control
};

// A mode's (stage index, report) list through a checkpoint, as two plain vectors.
template <class Report>
void save_stage_reports(checkpoint::OutArchive& ar,
                        const std::vector<std::pair<std::size_t, Report>>& list) {
  std::vector<std::size_t> stages;
  std::vector<Report> reports;
  for (const auto& [i, r] : list) {
    stages.push_back(i);
    reports.push_back(r);
  }
  ar(checkpoint::pod(stages), checkpoint::pod(reports));
}

template <class Report>
void load_stage_reports(checkpoint::InArchive& ar,
                        std::vector<std::pair<std::size_t, Report>>& list) {
  std::vector<std::size_t> stages;
  std::vector<Report> reports;
  ar(checkpoint::pod(stages), checkpoint::pod(reports));
  list.clear();
  for (std::size_t k = 0; k < stages.size(); ++k) list.emplace_back(stages[k], reports[k]);
}

// A mode's checkpoint state: its stage's control (if a stage of its runs), then its reports.
template <class Control, class Report>
void save_mode_state(checkpoint::OutArchive& ar, const std::optional<Control>& control,
                     const std::vector<std::pair<std::size_t, Report>>& reports) {
  const bool active = control.has_value();
  ar(active);
  if (active) ar(*control);
  save_stage_reports(ar, reports);
}

// The same loaded; `args` make a control whose state the archive then loads.
template <class Control, class Report, class... Args>
void load_mode_state(checkpoint::InArchive& ar, std::optional<Control>& control,
                     std::vector<std::pair<std::size_t, Report>>& reports, const Args&... args) {
  bool active = false;
  ar(active);
  control.reset();
  if (active) {
    control.emplace(args...);
    ar(*control);
  }
  load_stage_reports(ar, reports);
}

// The modes the load path's stages use, in the order of the table in stage_modes.cpp.
std::vector<std::unique_ptr<StageMode>> make_stage_modes(const DriverContext& c);

// Every mode's model-file keys, in the same order.
std::span<const io::StageModeKeys> stage_mode_keys();

}  // namespace vorodec::run
