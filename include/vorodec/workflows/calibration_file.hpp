#pragma once
// The calibration file (TOML) of `vorodec calibrate`: the tests to run (model files plus
// overrides), the parameters to vary, ties between model keys, the laboratory targets, the seeds
// and the budget. Keys are documented in README.md ("Calibration").
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "vorodec/input/model_file.hpp"

namespace vorodec::workflows {

struct CalibrationTest {
  std::string name;  // folder name part and the name targets use
  std::filesystem::path model;
  std::vector<io::Override> overrides;
  double confining_stress = 0;  // Pa, read from the model, for envelope targets
};

struct CalibrationParameter {
  std::string name;        // a model key ("joints.jkn") or a free name used by ties
  bool model_key = false;  // set in every run (a free name only feeds ties)
  double min = 0, max = 0, start = 0;
  bool log_scale = false;
  // Targets proportional to this parameter (dimensional analysis: E with jkn, strengths with
  // contact strengths), for the first guess.
  std::vector<std::size_t> scales;
  std::string origin;  // "calibrate.toml:12", for messages
};

// A model key computed from parameters: key = c x p1 x p2 / p3 ...
struct Tie {
  std::string key;
  double constant = 1;
  std::vector<std::size_t> times, divided_by;  // parameters
  std::string origin;
};

enum class TargetKind { summary, history, envelope_cohesion, envelope_friction };

// A point of a run's history: where `column` first reaches `value` (interpolated between rows), or,
// when column is "stage", the row that marks `stage` ("creep190:end").
struct HistoryPoint {
  std::string column{};  // "time", "axial_strain", "axial_stress", ... or "stage"
  double value = 0;
  std::string stage{};
  std::string key() const;
};

// What a target reads from one run: a summary.json number (by name, or by its dotted path
// "acoustic_emission.b_value"), or a history.csv column's value at a point, optionally as its
// change since a `from` point (a strain from the end of the hydrostatic stage, a stage's creep).
struct RunQuantity {
  std::string name;  // the summary name or path, or the history column
  bool history = false;
  HistoryPoint at{};
  HistoryPoint from{};      // column empty: the value itself; else the change since this point
  std::string key() const;  // one text per distinct quantity
};

// What `q` reads from the finished run in `run_dir` (summary.json, history.csv); NaN when the run
// did not produce it (no such number or column, or the run never reached the `at` point).
double run_quantity(const std::filesystem::path& run_dir, const RunQuantity& q);

struct CalibrationTarget {
  std::string name;
  std::string quantity;  // as the file gives it: a summary.json number, history.<column>, or
                         // cohesion_Pa / friction_angle_deg
  RunQuantity reads;     // summary and history targets
  TargetKind kind = TargetKind::summary;
  std::vector<std::size_t> tests;  // one for a summary key; two or more for an envelope
  double value = 0;
  double weight = 1;
  double tolerance = 0;  // relative (0.03 = 3 %), or absolute in the quantity's unit
  bool absolute = false;
  std::string origin;  // "calibrate.toml:40: target 'UCS'", for messages
};

struct CalibrationPlan {
  std::filesystem::path file;
  std::string title;
  std::filesystem::path output;  // relative to the working directory
  std::vector<std::uint64_t> seeds;
  long max_runs = 0;            // model runs, the sensitivity round included
  double max_wall_seconds = 0;  // s
  double step = 0.1;            // the sensitivity round's relative step (log scale: ln(1.1))
  int linearised_steps = 8;     // Gauss-Newton steps after the sensitivity round, at most
  bool secant_update = true;    // each step's secant corrects their Jacobian (Broyden)
  std::vector<CalibrationTest> tests;
  std::vector<CalibrationParameter> parameters;
  std::vector<Tie> ties;
  std::vector<CalibrationTarget> targets;
};

// The overrides of one run: the test's own, the seed, the parameters (model keys) and the ties.
std::vector<io::Override> run_overrides(const CalibrationPlan& plan, std::size_t test,
                                        std::uint64_t seed, const std::vector<double>& values);

// Throws ModelFileError (file, key and line) for bad input, including a parameter bound that a
// test's model file refuses (a negative stiffness, a friction angle above 90 degrees).
CalibrationPlan read_calibration_file(const std::filesystem::path& file);

}  // namespace vorodec::workflows
