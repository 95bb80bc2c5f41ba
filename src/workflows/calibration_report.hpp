#pragma once
// What `vorodec calibrate` writes: history.csv (one row per evaluation), sensitivity.csv (the
// micro-macro relations of each sensitivity round), the calibrated model files and report.md.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "vorodec/workflows/calibration_file.hpp"

namespace vorodec::workflows {

// One parameter set, run as every test x every seed.
struct Evaluation {
  std::size_t index = 0;       // 1, 2, ...: its folder runs/e0001
  std::string phase;           // start, dimensional, sensitivity, linearised, optimiser, rescaled
  std::vector<double> values;  // per parameter
  std::vector<double> mean, scatter, scaled_error;  // per target: over the seeds; error/tolerance
  double objective = INFINITY;                      // weighted mean of scaled_error^2
  double worst = INFINITY;     // largest |scaled_error|: 1 or less when every target is met
  std::size_t runs = 0;        // runs used up to and including this evaluation
  double wall_seconds = 0;     // s, its longest run
  double elapsed_seconds = 0;  // s of the calibration when it ended
  int failed_runs = 0;         // runs that exited non-zero
  std::size_t best = 0;        // the best evaluation so far, this one included
};

// A one-at-a-time round around one evaluation; matrices are targets x parameters, row-major.
struct Sensitivity {
  std::size_t base = 0;                  // evaluation
  std::vector<std::size_t> evaluations;  // one per parameter
  std::vector<double> jacobian;          // d(error / tolerance) / d(unit coordinate)
  std::vector<double> elasticity;        // d ln(target) / d ln(parameter)
};

void write_history(const std::filesystem::path& out, const CalibrationPlan& plan,
                   const std::vector<Evaluation>& history);
void write_sensitivity(const std::filesystem::path& out, const CalibrationPlan& plan,
                       const std::vector<Evaluation>& history,
                       const std::vector<Sensitivity>& rounds);
// calibrated_<model>.toml per model file of the tests: the model as base plus the calibrated keys.
void write_calibrated_models(const std::filesystem::path& out, const CalibrationPlan& plan,
                             const Evaluation& best);
void write_report(const std::filesystem::path& out, const CalibrationPlan& plan,
                  const std::vector<Evaluation>& history, const std::vector<Sensitivity>& rounds,
                  const Evaluation& best, bool converged, double elapsed_seconds);

}  // namespace vorodec::workflows
