#pragma once
// Whole-model runs for the published cases: run the real command, read what it wrote.
#include <filesystem>
#include <string>
#include <vector>

namespace vorodec::verification {

struct ModelRun {
  std::string summary;  // summary.json text
  double seconds = 0;   // wall time
  int exit_code = -1;
  std::filesystem::path out;
};

// `vorodec run MODEL --no-vtk --out OUT ARGS`, console output to OUT/log.txt.
ModelRun run_model(const std::string& binary, const std::filesystem::path& model,
                   const std::filesystem::path& out, const std::string& args = "");

// `--set key=value` for each top-level dotted key of a model file (a set written over its base,
// as models/ucs_marble_two_nu.toml), so another model on the same base can run with it.
std::string set_arguments(const std::filesystem::path& model);

// The first number or string named `key` in a summary.json's text, depth first in the file's
// order (a nested key by its own name: "tensile" in "cracks"); NaN or "" if absent.
double json_number(const std::string& json, const std::string& key);
std::string json_string(const std::string& json, const std::string& key);

// A CSV file as a header and rows of cells.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  // Index of a column by name; -1 if absent.
  int column(const std::string& name) const;
  // A row's value in a named column, NaN if absent or not a number.
  double number(std::size_t row, const std::string& name) const;
};
Table read_table(const std::filesystem::path& csv);

struct CaseResult;
// A row judged by its relative error |measured - expected| / |expected| (1 when not finite).
CaseResult relative(std::string id, std::string name, std::string reference, double expected,
                    double measured, double tolerance, std::string settings, double seconds);
// Energy balance at the end of a run (docs/theory.md §12), from the last row of its history:
// (boundary work - strain - kinetic - damping - friction - breakage) / boundary work, judged at
// 1 %.
CaseResult energy_balance(const std::string& id, const ModelRun& run, const std::string& settings);

// The loading rate must not decide the UCS: `run`'s peak against the same model run at half the
// platen speed (2.5e-3 m/s, written to `half_out`), judged at 2 %.
CaseResult half_rate_ucs(const std::string& id, const std::string& binary,
                         const std::filesystem::path& model, const ModelRun& run,
                         const std::filesystem::path& half_out);

}  // namespace vorodec::verification
