#pragma once
// Runs a list of model runs, each a `vorodec run` child process in its own folder, `jobs` at a
// time. A list run again on the same folders continues: finished cases are kept, stopped ones
// resume from their checkpoints. Shared by `vorodec batch` and `vorodec calibrate`.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vorodec/io/json.hpp"
#include "vorodec/workflows/batch_file.hpp"

namespace vorodec::workflows {

struct CaseOptions {
  long max_steps = 0;  // > 0: passed to every case as --max-steps
  bool write_vtk = true;
  // The `vorodec` command the cases run: this process's own, unless it is not that command (the
  // Python module).
  std::filesystem::path executable = "/proc/self/exe";
};

struct CaseOutcome {
  int exit_code = 0;
  double wall_seconds = 0;  // s, a resumed case's earlier parts included
  bool kept = false;        // it had finished before with the same command and model files
};

// Runs the cases `mine` (indices into `cases`) in out/<case name>/; `who` prefixes each progress
// line. Returns the outcome of each case run.
std::map<std::size_t, CaseOutcome> run_cases(const std::vector<BatchCase>& cases,
                                             const std::vector<std::size_t>& mine,
                                             const std::filesystem::path& out,
                                             const CaseOptions& options, int jobs,
                                             const std::string& who);

// A run's summary.json, parsed; null when the run wrote none or it does not parse.
io::Json read_summary(const std::filesystem::path& file);

// A summary's value named `name`: a top-level key, a nested one by its own name
// ("crack_initiation_stress_Pa" in "failure_stages") or by its dotted path
// ("acoustic_emission.b_value", "corrosion_stages.1.failure_time_s"); null when absent.
io::Json summary_value(const io::Json& summary, const std::string& name);

std::string read_text(const std::filesystem::path& file);

}  // namespace vorodec::workflows
