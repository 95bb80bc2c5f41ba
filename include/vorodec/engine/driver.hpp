#pragma once
// A run is a driver, which decides what the solver does next, and observers, which sample the
// state when the driver says so (observers.hpp). The driver never writes a file; an observer
// never moves a block.
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vorodec/checkpoint/archive.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/engine/summary.hpp"
#include "vorodec/io/json_fwd.hpp"
#include "vorodec/measure/specimen.hpp"

namespace vorodec::run {

// A pressure-bar test's bars, for the outputs (outputs/shpb_output).
struct BarsView {
  const loading::ShpbConfig& cfg;
  // Pa, compression +: the stress in each bar at x m from its face (0: the face itself; else a
  // gauge's position) at t s, time 0 being the pulse's arrival at the specimen.
  std::function<double(double, double)> incident, transmitted;
  double specimen_width, specimen_length;  // m, initial
  double recorded_until = 0;               // s: the bars' record ends here
  // s: how far past a face time the analysis reads the gauges (recorded bars: the gauges'
  // travel times; exact bars: 0, their later gauge values follow from the faces' record).
  double reach = 0;
};

// What observers read of a run, after a step or a stage transition.
struct RunView {
  const model::Model& model;
  const solver::Solver& solver;
  const geometry::Tessellation& specimen;
  const measure::SpecimenState& state;
  double platen_velocity;          // m/s, top platen, compression +
  int stage;                       // index of the current stage
  const BarsView* bars = nullptr;  // a pressure-bar test's
  // Columns the load path adds to history.csv (a stage mode's clock, say); none if null.
  const class ExtraColumns* columns = nullptr;
};

// history.csv columns of a load path's own: their names, fixed for the run, and their values now.
class ExtraColumns {
 public:
  virtual ~ExtraColumns() = default;
  virtual std::vector<std::string> column_names() const = 0;
  virtual void column_values(std::vector<double>& row) const = 0;  // appended in name order
};

// When to sample: a history row, an output frame (VTK and rose.csv), under this label.
struct Sample {
  std::string label;
  bool row = false;
  bool frame = false;
};

class Observers;

// What a person is told of the run's progress.
struct ProgressReport {
  std::size_t stage = 0, stages = 1;
  std::string stage_name;
  long steps = 0;
  double stress = 0;  // Pa
  // 0..1 and monotone within the stage where its end is known ahead (a duration, a strain, a
  // stress); NaN where it is not (a post-peak end), and then `waiting` says what is awaited.
  double fraction = std::nan("");
  std::string waiting;
  std::string clock;  // creep stages: simulated time in days
};

// How the load path ended, for the summary.
struct DriverOutcome {
  int exit_code = 0;  // RunSummary::exit_code
  std::string status = "finished";
  double peak = 0, trough = 0;  // Pa, largest and smallest axial stress
  std::vector<bool> stalled;    // per stage: it ended because it could not reach its target
};

class Driver {
 public:
  virtual ~Driver() = default;
  // One solver step or one transition (a stage's start or end), telling the observers when to
  // sample.
  virtual void advance(Observers& observers) = 0;
  virtual bool finished() const = 0;
  // Between two steps, where a checkpoint can be taken and resumed from.
  virtual bool resumable() const = 0;
  virtual RunView view() const = 0;
  virtual ProgressReport progress() const = 0;
  virtual const DriverOutcome& outcome() const = 0;
  // Adds what the load path did to summary.json (its stages' reports), if anything.
  virtual void summarise(io::Json& summary) const = 0;
  virtual void save(checkpoint::OutArchive& ar) const = 0;
  virtual void load(checkpoint::InArchive& ar) = 0;
};

}  // namespace vorodec::run
