// `vorodec batch`: one results.csv row per case, each the numbers of the case run alone; a failed
// case is a row, not a crash; bad batch input exits 2 with file:line before anything runs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_support.hpp"

using vorodec::testing::json_number;
using vorodec::testing::Outcome;
using vorodec::testing::run_capture;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// results.csv as rows of named fields (quoted fields may hold commas).
std::vector<std::map<std::string, std::string>> read_table(const fs::path& file) {
  std::vector<std::vector<std::string>> lines;
  std::istringstream in(read(file));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        fields.emplace_back();
      else
        fields.back() += c;
    }
    lines.push_back(fields);
  }
  std::vector<std::map<std::string, std::string>> rows;
  for (std::size_t r = 1; r < lines.size(); ++r) {
    rows.emplace_back();
    for (std::size_t i = 0; i < lines[0].size() && i < lines[r].size(); ++i)
      rows.back()[lines[0][i]] = lines[r][i];
  }
  return rows;
}

class Batch : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vorodec_batch_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  const std::string models = std::string(VORODEC_SOURCE_DIR) + "/tests/models/";
  fs::path dir_;
};

}  // namespace

TEST_F(Batch, ResultsTableHasOneRowPerCaseInCaseOrder) {
  const Outcome o =
      run_capture("batch " + models + "batch_small.toml --no-vtk --out " + (dir_ / "out").string());
  EXPECT_EQ(o.code, 5) << o.output;  // the step_limit cases stop at their limit (exit 4)
  const auto rows = read_table(dir_ / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 4u) << o.output;
  const char* names[] = {"small_seed=11", "small_seed=12", "step_limit_seed=11",
                         "step_limit_seed=12"};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].at("case"), names[i]);
    EXPECT_TRUE(fs::exists(dir_ / "out" / names[i] / "history.csv")) << names[i];
  }
  EXPECT_EQ(rows[1].at("seed"), "12");
  EXPECT_EQ(rows[2].at("solver.max_steps"), "300");
  EXPECT_EQ(rows[0].at("solver.max_steps"), "");
}

TEST_F(Batch, RunAgainOnItsFinishedFolderKeepsEveryCaseAndRewritesTheTable) {
  const std::string command =
      "batch " + models + "batch_small.toml --no-vtk --out " + (dir_ / "out").string();
  ASSERT_EQ(run_capture(command).code, 5);
  const auto first = read_table(dir_ / "out" / "results.csv");
  const Outcome again = run_capture(command);
  EXPECT_EQ(again.code, 5) << again.output;  // was: "lost track of the running cases", exit 1
  EXPECT_NE(again.output.find("kept, it finished before"), std::string::npos) << again.output;
  const auto rows = read_table(dir_ / "out" / "results.csv");
  ASSERT_EQ(rows.size(), first.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    EXPECT_EQ(rows[i].at("peak_stress_Pa"), first[i].at("peak_stress_Pa"));
}

TEST_F(Batch, FailedCaseIsARowWithItsExitCode) {
  run_capture("batch " + models + "batch_small.toml --no-vtk --out " + (dir_ / "out").string());
  const auto rows = read_table(dir_ / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[2].at("exit_code"), "4");
  EXPECT_EQ(rows[2].at("status"), "step limit");
  EXPECT_EQ(rows[2].at("steps"), "300");
}

TEST_F(Batch, RowEqualsTheSameCaseRunAlone) {
  // The case of the batch (e2e_small with seed = 12 set by the grid), and the same model edited
  // by hand and run on its own.
  std::string model = read(models + "e2e_small.toml");
  model.replace(model.find("seed = 11"), 9, "seed = 12");
  const fs::path alone = write("e2e_small_seed12.toml", model);
  const Outcome a = run_capture("run " + alone.string() + " --threads 1 --no-vtk --out " +
                                (dir_ / "alone").string());
  ASSERT_EQ(a.code, 0) << a.output;
  const Outcome b = run_capture("batch " + models + "batch_small.toml --no-vtk --jobs 2 --out " +
                                (dir_ / "b").string());
  const auto rows = read_table(dir_ / "b" / "results.csv");
  ASSERT_EQ(rows.size(), 4u) << b.output;
  const auto& row = rows[1];
  ASSERT_EQ(row.at("case"), "small_seed=12");
  const std::string summary = read(dir_ / "alone" / "summary.json");
  EXPECT_EQ(row.at("exit_code"), "0");
  // The same numbers (the table writes them as summary.json rounds them, in its own text).
  for (const char* key : {"peak_stress_Pa", "youngs_modulus_Pa", "poisson_ratio", "steps"})
    EXPECT_EQ(std::stod(row.at(key)), json_number(summary, key)) << key;
  EXPECT_EQ(std::stod(row.at("cracks_tensile")), json_number(summary, "tensile"));
  EXPECT_EQ(read(dir_ / "b" / "small_seed=12" / "history.csv"),
            read(dir_ / "alone" / "history.csv"));
}

TEST_F(Batch, UnknownOverrideKeyExitsWithTwoNamingTheBatchFileLine) {
  const fs::path batch = write("bad.toml", "model = \"" + models +
                                               "e2e_small.toml\"\n"
                                               "[grid]\n"
                                               "\"loading.confining_stresss\" = [0, 1e6]\n");
  const Outcome o = run_capture("batch " + batch.string() + " --out " + (dir_ / "out").string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(batch.string() + ":3: override 'loading.confining_stresss'"),
            std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("did you mean 'confining_stress'"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out")) << "nothing runs after bad input";
}

TEST_F(Batch, UnknownBatchKeyAndMissingModelAreNamed) {
  const fs::path typo =
      write("typo.toml", "model = \"" + models + "e2e_small.toml\"\nouptut = \"x\"\n");
  Outcome o = run_capture("batch " + typo.string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(typo.string() + ":2: key 'ouptut': unknown key (did you mean 'output'?)"),
            std::string::npos)
      << o.output;
  const fs::path missing = write("missing.toml", "[[case]]\nmodel = \"no_such_model.toml\"\n");
  o = run_capture("batch " + missing.string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(missing.string() + ":2: key 'case[0].model'"), std::string::npos)
      << o.output;
}

TEST_F(Batch, SetOptionOverridesAModelKeyAndRejectsUnknownOnes) {
  const std::string model = models + "e2e_small.toml";
  Outcome o = run_capture("check " + model + " --set loading.confining_stress=2e6 --set seed=5");
  EXPECT_EQ(o.code, 0) << o.output;
  o = run_capture("check " + model + " --set solver.local_damping=1.5");
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("--set: override 'solver.local_damping' of " + model + ": must be < 1"),
            std::string::npos)
      << o.output;
  o = run_capture("check " + model + " --set stage[3].end_time=1");
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("'stage' has 1 entries"), std::string::npos) << o.output;
}
