#pragma once
// `vorodec calibrate`: from laboratory targets to contact parameters. Every evaluation runs each
// test once per seed (the same seeds, so the same specimens and Weibull draws, every time: common
// random numbers); the objective is the weighted mean of (error / tolerance)^2 over the targets.
// The search: the start; a first guess by dimensional analysis (parameters scale the targets they
// are declared proportional to); a one-at-a-time sensitivity round and the linearised step it
// gives; then NLopt's BOBYQA within the bounds, until every target is within its tolerance or the
// budget is spent. Evaluations live in numbered folders, so a stopped calibration run again
// replays its finished runs and continues.
#include <filesystem>

namespace vorodec::workflows {

struct CalibrateOptions {
  std::filesystem::path file;
  std::filesystem::path out;  // empty: the file's `output`
  int jobs = 0;               // runs at a time per process; 0: all cores (1 per MPI rank)
  bool check = false;         // validate the file (and the bounds against the models), run nothing
  std::filesystem::path executable = "/proc/self/exe";  // the `vorodec` that runs the tests
};

// Exit code: 0 every target within tolerance; 5 the budget ran out first (the best set is
// written all the same); 2 bad input.
int calibrate(const CalibrateOptions& options);

}  // namespace vorodec::workflows
