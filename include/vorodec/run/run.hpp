#pragma once
// Runs a model file's load path with its outputs, stops it with a checkpoint and resumes it.
#include <filesystem>
#include <functional>
#include <vector>

#include "vorodec/engine/driver.hpp"
#include "vorodec/engine/summary.hpp"
#include "vorodec/geometry/tessellation.hpp"
#include "vorodec/input/model_file.hpp"

namespace vorodec::run {

struct RunOptions {
  std::filesystem::path out;  // results folder
  long max_steps = 0;         // > 0: stop after this many steps (short mode)
  bool write_vtk = true;
  bool progress = true;  // progress bar (terminal) or progress lines
  // > 0: at the first step from this one where the run can resume, write a checkpoint and stop
  // (exit code kStoppedForResume), as SIGINT or SIGTERM do.
  long stop_at_step = 0;
  // Called with the driver's report as often as the progress line is (the Python module's
  // callback); independent of `progress`.
  std::function<void(const ProgressReport&)> on_progress;
};

// Exit code of a run stopped with a checkpoint written (signal or --stop-at-step):
// `vorodec resume DIR` continues it.
inline constexpr int kStoppedForResume = 6;
// Exit code of a run stopped as numerically unstable; the last good state is written.
inline constexpr int kStoppedUnstable = 3;
// The checkpoint file in a results folder.
inline constexpr const char* kCheckpointFile = "checkpoint.vck";

// Runs the load path. `overrides` are those cfg was read with (a checkpoint records them).
RunSummary run_model(const io::ModelConfig& cfg, const geometry::Tessellation& specimen,
                     const RunOptions& options, const std::vector<io::Override>& overrides = {});

// Continues the run whose checkpoint is in `dir`, with the options it was started with but for
// stop_at_step and progress. Throws checkpoint::CheckpointError (no, foreign, truncated or corrupt
// checkpoint) and io::ModelFileError (the model file changed since).
RunSummary resume_run(const std::filesystem::path& dir, long stop_at_step, bool progress,
                      std::function<void(const ProgressReport&)> on_progress = {});

// SIGINT and SIGTERM then stop a run at its next step with a checkpoint (kStoppedForResume); a
// second one ends it at once. Runs install this when their stepping starts, and forget an earlier
// run's stop then (a process may run several: the Python module).
void stop_on_signals();
// Stops the running run at its next step with a checkpoint, as a signal does (from any thread).
void request_stop();
// The signal that stopped the last run (0: none, or stopped by request_stop or stop_at_step).
int stop_signal_received();

}  // namespace vorodec::run
