#pragma once
// Runs a model file's load path with its outputs, stops it with a checkpoint and resumes it.
#include <filesystem>
#include <vector>

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
};

// Exit code of a run stopped with a checkpoint written (signal or --stop-at-step):
// `vorodec resume DIR` continues it.
inline constexpr int kStoppedForResume = 6;
// The checkpoint file in a results folder.
inline constexpr const char* kCheckpointFile = "checkpoint.vck";

// Runs the load path. `overrides` are those cfg was read with (a checkpoint records them).
RunSummary run_model(const io::ModelConfig& cfg, const geometry::Tessellation& specimen,
                     const RunOptions& options, const std::vector<io::Override>& overrides = {});

// Continues the run whose checkpoint is in `dir`, with the options it was started with but for
// stop_at_step and progress. Throws checkpoint::CheckpointError (no, foreign, truncated or corrupt
// checkpoint) and io::ModelFileError (the model file changed since).
RunSummary resume_run(const std::filesystem::path& dir, long stop_at_step, bool progress);

// SIGINT and SIGTERM then stop a run at its next step with a checkpoint (kStoppedForResume); a
// second one ends it at once. Runs install this when their stepping starts.
void stop_on_signals();

}  // namespace vorodec::run
