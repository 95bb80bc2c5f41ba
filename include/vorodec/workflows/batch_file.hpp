#pragma once
// The batch file (TOML): a programme of model runs, each a model file plus overrides, and/or a grid
// of override values whose every combination is one case. Keys are documented in README.md.
#include <filesystem>
#include <string>
#include <vector>

#include "vorodec/input/model_file.hpp"

namespace vorodec::workflows {

struct BatchCase {
  std::string name;             // the case's folder inside the batch's results folder
  std::filesystem::path model;  // model file
  std::vector<io::Override> overrides;
};

struct BatchPlan {
  std::filesystem::path file;
  std::string title;
  std::filesystem::path output;      // results folder (relative to the working directory)
  std::vector<std::string> columns;  // every overridden key, in order of first appearance
  std::vector<BatchCase> cases;
};

// Throws ModelFileError (file, key and line) for bad input. Model files are not read here.
BatchPlan read_batch_file(const std::filesystem::path& file);

// The value a case gives `key` (TOML text), or "" where the case keeps the model's value.
std::string override_value(const BatchCase& c, const std::string& key);

}  // namespace vorodec::workflows
