#pragma once
// What every driver does around a solver step, written once: the step limit, the outcome of an
// instability, the stress extremes and the samples due.
#include <algorithm>
#include <string>

#include "vorodec/engine/driver.hpp"

namespace vorodec::run {

// The run's step limit: --max-steps (a short run, exit 0) or the model file's solver.max_steps
// (exit 4).
struct StepLimit {
  long steps;
  bool from_option;
  // Whether `done` steps reach it; then the outcome says so.
  bool reached(long done, DriverOutcome& o) const {
    if (done < steps) return false;
    o.status = from_option ? "stopped at --max-steps" : "step limit";
    o.exit_code = from_option ? 0 : 4;
    return true;
  }
};

// A numerical instability ends the run (exit 3).
inline void mark_unstable(DriverOutcome& o, const char* what) {
  o.exit_code = 3;
  o.status = std::string("unstable: ") + what;
}

// The largest and smallest axial stress so far (Pa).
inline void track_extremes(DriverOutcome& o, double stress) {
  o.peak = std::max(o.peak, stress);
  o.trough = std::min(o.trough, stress);
}

// What is due after step `step`: a history row every `history_steps`, a frame every `vtk_steps`.
struct Due {
  bool row, frame;
};
inline Due due(long step, long history_steps, long vtk_steps) {
  return {step % history_steps == 0, step % vtk_steps == 0};
}

}  // namespace vorodec::run
