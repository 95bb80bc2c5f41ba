#pragma once
// Runs a list of model runs, each a `vorodec run` child process in its own folder, `jobs` at a
// time. A list run again on the same folders continues: finished cases are kept, stopped ones
// resume from their checkpoints. Shared by `vorodec batch` and `vorodec calibrate`.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vorodec/io/batch_file.hpp"

namespace vorodec::app {

struct CaseOptions {
  long max_steps = 0;  // > 0: passed to every case as --max-steps
  bool write_vtk = true;
};

struct CaseOutcome {
  int exit_code = 0;
  double wall_seconds = 0;  // s, a resumed case's earlier parts included
  bool kept = false;        // it had finished before with the same command and model files
};

// Runs the cases `mine` (indices into `cases`) in out/<case name>/; `who` prefixes each progress
// line. Returns the outcome of each case run.
std::map<std::size_t, CaseOutcome> run_cases(const std::vector<io::BatchCase>& cases,
                                             const std::vector<std::size_t>& mine,
                                             const std::filesystem::path& out,
                                             const CaseOptions& options, int jobs,
                                             const std::string& who);

// One field of a summary.json as written: a top-level key or a nested one by its own name
// ("crack_initiation_stress_Pa"); "" if absent.
std::string summary_field(const std::string& text, const std::string& key);

std::string read_text(const std::filesystem::path& file);

}  // namespace vorodec::app
