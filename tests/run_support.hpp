#pragma once
// Running the real `vorodec` command from a test and reading what it wrote.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "model_runs.hpp"

namespace vorodec::testing {

namespace fs = std::filesystem;

// Exit code of `vorodec <args>` (its output discarded).
inline int run_vorodec(const std::string& args) {
  const int status =
      std::system((std::string(VORODEC_BINARY) + " " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Outcome {
  int code;
  std::string output;  // stdout and stderr together
};

// Exit code and console output of `vorodec <args>`.
inline Outcome run_capture(const std::string& args) {
  const std::string cmd = std::string(VORODEC_BINARY) + " " + args + " 2>&1";
  Outcome o{-1, {}};
  FILE* p = popen(cmd.c_str(), "r");
  char buf[512];
  while (fgets(buf, sizeof buf, p)) o.output += buf;
  const int status = pclose(p);
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

// One folder per process: ctest runs each test as its own process, several at a time.
inline fs::path base_dir() {
  return fs::temp_directory_path() / ("vorodec_test_" + std::to_string(getpid()));
}

// An empty results folder `name` inside base_dir().
inline fs::path out_dir(const std::string& name) {
  const fs::path d = base_dir() / name;
  fs::remove_all(d);
  return d;
}

// The numeric cells of a CSV file after its header; text cells are skipped.
inline std::vector<std::vector<double>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (end != cell.c_str() && *end == '\0') row.push_back(v);
    }
    rows.push_back(row);
  }
  return rows;
}

inline std::string slurp(const fs::path& f) {
  std::ifstream in(f);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A number in summary.json, a nested one by its own name (verification/cases/model_runs.hpp).
using verification::json_number;

}  // namespace vorodec::testing
