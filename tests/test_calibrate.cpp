// `vorodec calibrate`: from targets back to the parameters that produced them; a calibration run
// again replays its runs; bad calibration input exits 2 with file, key and line.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "run_support.hpp"
#include "vorodec/workflows/calibration_file.hpp"

using vorodec::testing::json_number;
using vorodec::testing::out_dir;
using vorodec::testing::run_capture;
using vorodec::testing::run_vorodec;
using vorodec::testing::slurp;
namespace fs = std::filesystem;

namespace {

const std::string kModel = std::string(VORODEC_SOURCE_DIR) + "/tests/models/e2e_small.toml";

// The planted parameters: jkn and the cohesion; jks and the tension follow by fixed ratios.
constexpr double kJkn = 1.8e13, kCohesion = 24e6;
constexpr const char* kTies =
    "[tie]\n\"joints.jks\" = \"0.40556 * joints.jkn\"\n"
    "\"joints.tension.mean\" = \"0.58333 * joints.cohesion.mean\"\n";

// A calibration of the small UCS model: jkn and the cohesion from E and the UCS, seeds 11 and 12.
std::string calibration(double e_target, double ucs_target, const std::string& extra = "",
                        const std::string& model = kModel) {
  return fmt::format(
      "title = \"planted\"\nseeds = [11, 12]\n[budget]\nruns = 60\nwall_time = 600\n"
      "[[test]]\nname = \"ucs\"\nmodel = \"{}\"\n"
      "[[parameter]]\nkey = \"joints.jkn\"\nmin = 5e12\nmax = 1e14\nstart = {}\nscale = "
      "\"log\"\nscales = [\"E\"]\n"
      "[[parameter]]\nkey = \"joints.cohesion.mean\"\nmin = 5e6\nmax = 1e8\nstart = {}\nscale = "
      "\"log\"\nscales = [\"UCS\"]\n{}"
      "[[target]]\nname = \"E\"\ntest = \"ucs\"\nquantity = \"youngs_modulus_Pa\"\nvalue = {}\n"
      "tolerance = 0.01\n"
      "[[target]]\nname = \"UCS\"\ntest = \"ucs\"\nquantity = \"peak_stress_Pa\"\nvalue = {}\n"
      "tolerance = 0.01\n{}",
      model, 2 * kJkn, kCohesion / 2, kTies, e_target, ucs_target, extra);
}

fs::path write(const fs::path& dir, const std::string& name, const std::string& text) {
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

// The value the calibrated model file gives `key` (a line "key = value  # ...").
double calibrated(const fs::path& file, const std::string& key) {
  std::istringstream in(slurp(file));
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + " = ", 0) == 0) return std::stod(line.substr(key.size() + 3));
  return std::nan("");
}

using Row = std::map<std::string, std::string>;

double num(const Row& r, const std::string& key) {
  return std::stod(r.at(key));
}

// history.csv, a row per evaluation keyed by the header.
std::vector<Row> history(const fs::path& out) {
  std::istringstream in(slurp(out / "history.csv"));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::istringstream h(line); std::getline(h, line, ',');) header.push_back(line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row row;
    std::istringstream cells(line);
    for (const std::string& key : header) std::getline(cells, row[key], ',');
    rows.push_back(row);
  }
  return rows;
}

// Each row's `best` is the best evaluation up to it: one meeting every target (worst <= 1) before
// any that does not, then the lower objective.
void expect_best_follows_the_rule(const std::vector<Row>& rows) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const bool meets = num(rows[i], "worst") <= 1, best_meets = num(rows[best], "worst") <= 1;
    if (i == 0 || (meets && !best_meets) ||
        (meets == best_meets && num(rows[i], "objective") < num(rows[best], "objective")))
      best = i;
    EXPECT_EQ(num(rows[i], "best"), static_cast<double>(best + 1)) << "evaluation " << i + 1;
  }
}

}  // namespace

TEST(Calibrate, RecoversPlantedParametersFromAWrongStartAndReplaysOnRerunUnderAnotherPathSpelling) {
  const fs::path dir = out_dir("calibrate_planted");
  // The targets: what the planted parameters give, mean over the two seeds.
  double e = 0, ucs = 0;
  for (const int seed : {11, 12}) {
    const fs::path run = dir / fmt::format("planted_{}", seed);
    ASSERT_EQ(
        run_vorodec(fmt::format(
            "run {} --no-vtk --threads 1 --out {} --set seed={} --set joints.jkn={} "
            "--set joints.jks={} --set joints.cohesion.mean={} --set "
            "joints.tension.mean={}",
            kModel, run.string(), seed, kJkn, 0.40556 * kJkn, kCohesion, 0.58333 * kCohesion)),
        0);
    const std::string summary = slurp(run / "summary.json");
    e += json_number(summary, "youngs_modulus_Pa") / 2;
    ucs += json_number(summary, "peak_stress_Pa") / 2;
  }
  // The model relative to the calibration file, whose path the rerun spells differently.
  const fs::path file =
      write(dir, "planted.toml", calibration(e, ucs, "", fs::relative(kModel, dir).string()));
  const fs::path out = dir / "calibration";
  const auto first = run_capture(fmt::format("calibrate {} --out {}", file.string(), out.string()));
  ASSERT_EQ(first.code, 0) << first.output;
  const fs::path model = out / "calibrated_e2e_small.toml";
  // Targets within 1 % pin jkn (E ~ jkn) to about 1 %, but the cohesion only as well as this
  // 40-block specimen's UCS follows it: between two evaluations of a CI run (2026-12-03) the UCS
  // rose 6 % for 3.7 % more cohesion (its failure sequence changed), and a set 3.2 % below the
  // planted cohesion met both targets. Recovery from a start 100 % off is checked to 5 %.
  EXPECT_NEAR(calibrated(model, "joints.jkn") / kJkn, 1.0, 0.03) << slurp(model);
  EXPECT_NEAR(calibrated(model, "joints.cohesion.mean") / kCohesion, 1.0, 0.05) << slurp(model);
  EXPECT_NEAR(calibrated(model, "joints.jks") / calibrated(model, "joints.jkn"), 0.40556, 1e-9);
  // The calibrated set is the one the last row of history.csv names as the best.
  const std::vector<Row> rows = history(out);
  expect_best_follows_the_rule(rows);
  const Row& best = rows.at(static_cast<std::size_t>(num(rows.back(), "best")) - 1);
  EXPECT_LE(num(best, "worst"), 1.0);
  EXPECT_NEAR(calibrated(model, "joints.jkn") / num(best, "joints.jkn"), 1.0, 1e-5);
  const std::string report = slurp(out / "report.md");
  EXPECT_NE(report.find("every target within its tolerance"), std::string::npos) << report;
  EXPECT_EQ(run_vorodec("check " + model.string()), 0);  // a model file as any other

  // Run again, the file and the folder named relative to the working directory (the file through
  // "./"), where the first run named them absolutely: every run is kept, the search takes the
  // same path to the same parameters.
  const std::string before = slurp(model);
  const auto again = run_capture(fmt::format("calibrate {} --out {}",
                                             (fs::relative(dir) / "." / "planted.toml").string(),
                                             fs::relative(out).string()));
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_EQ(again.output.find(": exit "), std::string::npos) << "a run ran again:\n"
                                                             << again.output;
  EXPECT_EQ(slurp(model), before);
}

// Tolerances of 1e-5 keep the search going to the end of its budget: every new best of the
// optimiser is followed by its rescaling, jkn by wanted / achieved E and the cohesion by wanted /
// achieved UCS, and a rescaled set that is the new best is where the optimiser starts again.
TEST(Calibrate, OptimisersNewBestIsRescaledOntoItsProportionalTargets) {
  const fs::path dir = out_dir("calibrate_rescaled");
  std::string text = calibration(3e10, 6e7);
  for (std::size_t at; (at = text.find("tolerance = 0.01")) != std::string::npos;)
    text.replace(at, 16, "tolerance = 0.00001");
  text.replace(text.find("runs = 60"), 9, "runs = 40");
  const fs::path file = write(dir, "c.toml", text);
  const auto o =
      run_capture(fmt::format("calibrate {} --out {}", file.string(), (dir / "out").string()));
  ASSERT_EQ(o.code, 5) << o.output;  // the budget ends it
  std::vector<Row> rows = history(dir / "out");
  expect_best_follows_the_rule(rows);
  int rescaled = 0;
  double best = INFINITY;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i]["phase"] == "rescaled") {
      ASSERT_GT(i, 0u);
      const auto& from = rows[i - 1];
      EXPECT_EQ(from.at("phase"), "optimiser");
      EXPECT_LE(num(from, "objective"), best);  // a new best
      EXPECT_NEAR(num(rows[i], "joints.jkn"), num(from, "joints.jkn") * 3e10 / num(from, "E_mean"),
                  1e-4 * num(rows[i], "joints.jkn"));
      EXPECT_NEAR(num(rows[i], "joints.cohesion.mean"),
                  num(from, "joints.cohesion.mean") * 6e7 / num(from, "UCS_mean"),
                  1e-4 * num(rows[i], "joints.cohesion.mean"));
      // A rescaled new best restarts the optimiser there: its first point is that set.
      if (num(rows[i], "objective") < std::min(best, num(from, "objective")) &&
          i + 1 < rows.size()) {
        EXPECT_EQ(rows[i + 1]["joints.jkn"] + rows[i + 1]["joints.cohesion.mean"],
                  rows[i]["joints.jkn"] + rows[i]["joints.cohesion.mean"]);
      }
      ++rescaled;
    }
    best = std::min(best, num(rows[i], "objective"));
  }
  EXPECT_GT(rescaled, 0) << slurp(dir / "out" / "history.csv");
}

TEST(Calibrate, HistoryPointReachedBeforeARunStoppedUnstableCounts) {
  // Stage "load" ends at 0.1 % strain; "crush" then overlaps its contacts beyond the limit (exit
  // 3, the last good state written). The stress at load:end is still the run's: the target is met.
  const fs::path dir = out_dir("calibrate_unstable_later");
  write(dir, "m.toml",
        fmt::format("base = \"{}\"\n[contact]\noverlap_limit = 0.2\n"
                    "[[stage]]\nname = \"load\"\nplaten_velocity = 0.02\nramp_time = 2e-4\n"
                    "end_axial_strain = 1e-3\n"
                    "[[stage]]\nname = \"crush\"\nplaten_velocity = 20.0\nend_axial_strain = 0.2\n",
                    kModel));
  const fs::path file =
      write(dir, "c.toml",
            "title = \"unstable later\"\nseeds = [11]\n[budget]\nruns = 4\nwall_time = 600\n"
            "[[test]]\nname = \"two\"\nmodel = \"m.toml\"\n"
            "[[parameter]]\nkey = \"joints.jkn\"\nmin = 5e12\nmax = 1e14\nstart = 1.8e13\n"
            "scale = \"log\"\n"
            "[[target]]\nname = \"stress\"\ntest = \"two\"\nquantity = \"history.axial_stress\"\n"
            "at = { stage = \"load:end\" }\nvalue = 32.76e6\ntolerance = 0.01\n");
  const auto o =
      run_capture(fmt::format("calibrate {} --out {}", file.string(), (dir / "out").string()));
  EXPECT_EQ(o.code, 0) << o.output;
  EXPECT_NE(slurp(dir / "out" / "runs" / "e0001" / "two_seed11" / "log.txt").find("unstable"),
            std::string::npos);
}

TEST(Calibrate, EvaluationStartsTheRunsThatTookLongestBeforeFirst) {
  // "long" strains five times as far as "short" but is listed second: the first evaluation runs
  // them in the listed order, the second (the sensitivity round) starts "long" first. One job at
  // a time, so the runs end in the order they start.
  const fs::path dir = out_dir("calibrate_longest_first");
  const std::string stage =
      "base = \"{}\"\n[[stage]]\nname = \"load\"\nplaten_velocity = 0.02\nramp_time = 2e-4\n"
      "end_axial_strain = {}\n";
  write(dir, "short.toml", fmt::format(fmt::runtime(stage), kModel, 2e-4));
  write(dir, "long.toml", fmt::format(fmt::runtime(stage), kModel, 1e-3));
  const fs::path file =
      write(dir, "c.toml",
            "title = \"longest first\"\nseeds = [11]\n[budget]\nruns = 6\nwall_time = 600\n"
            "[[test]]\nname = \"short\"\nmodel = \"short.toml\"\n"
            "[[test]]\nname = \"long\"\nmodel = \"long.toml\"\n"
            "[[parameter]]\nkey = \"joints.jkn\"\nmin = 5e12\nmax = 1e14\nstart = 1.8e13\n"
            "scale = \"log\"\n"
            "[[target]]\nname = \"stress\"\ntest = \"long\"\nquantity = \"history.axial_stress\"\n"
            "at = { stage = \"load:end\" }\nvalue = 1e9\ntolerance = 0.01\n");
  const auto o = run_capture(
      fmt::format("calibrate {} --out {} --jobs 1", file.string(), (dir / "out").string()));
  EXPECT_EQ(o.code, 5) << o.output;  // the budget spent: no stiffness gives 1 GPa at that strain
  const auto at = [&](const std::string& run) { return o.output.find(run + "_seed11: exit 0"); };
  ASSERT_NE(at("e0002/long"), std::string::npos) << o.output;
  EXPECT_LT(at("e0001/short"), at("e0001/long")) << o.output;
  EXPECT_LT(at("e0002/long"), at("e0002/short")) << o.output;
}

TEST(Calibrate, TargetNoTestProducesExitsTwoNamingTheTarget) {
  const fs::path dir = out_dir("calibrate_no_tension");
  const std::string extra =
      "[[target]]\nname = \"tension\"\ntest = \"ucs\"\nquantity = \"tensile_strength_Pa\"\n"
      "value = 10e6\ntolerance = 0.05\n";
  const fs::path file = write(dir, "c.toml", calibration(3e10, 6e7, extra));
  const auto o =
      run_capture(fmt::format("calibrate {} --out {}", file.string(), (dir / "out").string()));
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("c.toml:38: target 'tension'"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("tensile_strength_Pa"), std::string::npos) << o.output;
}

TEST(CalibrationTargets, ReadAHistoryColumnAtACrossingOrAStageOrItsChangeAndASummaryNumber) {
  using vorodec::workflows::run_quantity;
  using vorodec::workflows::RunQuantity;
  const fs::path dir = out_dir("calibrate_quantities");
  write(dir, "history.csv",
        "step,time,axial_strain,axial_stress,stage\n0,0,0,0,load:start\n10,1,0.001,2e7,load\n"
        "20,2,0.003,6e7,load\n30,3,0.004,5e7,load:end\n");
  write(dir, "summary.json",
        R"({"acoustic_emission": {"b_value": 1.5},)"
        R"( "corrosion_stages": [{"failure_time_s": 1}, {"failure_time_s": 7}]})");
  // Between the rows at strains 0.001 and 0.003: interpolated.
  EXPECT_DOUBLE_EQ(run_quantity(dir, {"axial_stress", true, {"axial_strain", 0.002}}), 4e7);
  EXPECT_DOUBLE_EQ(run_quantity(dir, {"axial_strain", true, {"time", 0.0}}), 0.0);
  EXPECT_DOUBLE_EQ(run_quantity(dir, {"axial_stress", true, {"stage", 0, "load:end"}}), 5e7);
  EXPECT_TRUE(std::isnan(run_quantity(dir, {"axial_stress", true, {"time", 9.0}})));  // never
  EXPECT_TRUE(std::isnan(run_quantity(dir, {"axial_stres", true, {"time", 1.0}})));
  // The change from a `from` point: a stage's strain, a strain since a stress was reached.
  EXPECT_DOUBLE_EQ(
      run_quantity(dir,
                   {"axial_strain", true, {"stage", 0, "load:end"}, {"stage", 0, "load:start"}}),
      0.004);
  EXPECT_DOUBLE_EQ(run_quantity(dir, {"axial_strain", true, {"time", 2.0}, {"axial_stress", 2e7}}),
                   0.002);
  EXPECT_TRUE(std::isnan(
      run_quantity(dir, {"axial_strain", true, {"time", 2.0}, {"stage", 0, "unload:end"}})));
  EXPECT_DOUBLE_EQ(run_quantity(dir, {"acoustic_emission.b_value"}), 1.5);
  EXPECT_DOUBLE_EQ(run_quantity(dir, {"corrosion_stages.1.failure_time_s"}), 7.0);
  EXPECT_TRUE(std::isnan(run_quantity(dir, {"corrosion_stages.x.failure_time_s"})));
  EXPECT_TRUE(std::isnan(run_quantity(dir, {"peak_stress_Pa"})));
}

// Each bad file: texts replaced in a good calibration, and what the message must name.
struct BadCalibration {
  std::string from, to, expected, from2 = "", to2 = "";
};

class CalibrateBadInput : public ::testing::TestWithParam<BadCalibration> {};

TEST_P(CalibrateBadInput, ExitsTwoWithFileKeyAndLine) {
  const BadCalibration& bad = GetParam();
  std::string text = calibration(3e10, 6e7);
  const auto at = text.find(bad.from);
  ASSERT_NE(at, std::string::npos) << bad.from;
  text.replace(at, bad.from.size(), bad.to);
  if (!bad.from2.empty()) text.replace(text.find(bad.from2), bad.from2.size(), bad.to2);
  const fs::path dir = out_dir("calibrate_bad");
  const fs::path file = write(dir, "bad.toml", text);
  const auto o = run_capture("calibrate " + file.string() + " --check");
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(bad.expected), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir / "runs"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CalibrateBadInput,
    ::testing::Values(
        BadCalibration{"title = ", "titel = ", "bad.toml:1: key 'titel': unknown key"},
        BadCalibration{"min = 5e12\nmax = 1e14", "min = 1e14\nmax = 5e12",
                       "bad.toml:12: key 'parameter[0].max': bounds reversed"},
        BadCalibration{"key = \"joints.jkn\"\nmin = 5e12", "key = \"joints.jkn\"\nmin = -5e12",
                       "key 'parameter[0].min': joints.jkn = -5000000000000: test 'ucs' "
                       "refuses it: must be > 0 Pa/m",
                       "scale = \"log\"\nscales = [\"E\"]", "scale = \"linear\"\nscales = [\"E\"]"},
        BadCalibration{"quantity = \"peak_stress_Pa\"", "quantity = \"peak_strength\"",
                       "key 'target[1].quantity': 'peak_strength' is not produced by any test"},
        BadCalibration{"seeds = [11, 12]", "seeds = []", "bad.toml:2: key 'seeds'"},
        BadCalibration{"seeds = [11, 12]", "seeds = [11, 12]\nlinearised_steps = 101",
                       "bad.toml:3: key 'linearised_steps'"},
        BadCalibration{"seeds = [11, 12]", "seeds = [11, 12]\nsecant_update = 1",
                       "bad.toml:3: key 'secant_update'"},
        BadCalibration{"quantity = \"peak_stress_Pa\"", "quantity = \"history.axial_stress\"",
                       "key 'target[1].at': a history quantity needs `at`"},
        BadCalibration{"quantity = \"peak_stress_Pa\"",
                       "quantity = \"peak_stress_Pa\"\nat = { time = 1.0 }",
                       "key 'target[1].at': only a history.<column> quantity"},
        BadCalibration{"quantity = \"peak_stress_Pa\"",
                       "quantity = \"history.axial_stress\"\nat = { time = 1.0, stage = \"a\" }",
                       "key 'target[1].at': give one column"},
        BadCalibration{"quantity = \"peak_stress_Pa\"",
                       "quantity = \"peak_stress_Pa\"\nfrom = { time = 1.0 }",
                       "key 'target[1].from': only a history.<column> quantity"},
        BadCalibration{"quantity = \"peak_stress_Pa\"",
                       "quantity = \"history.axial_strain\"\nat = { time = 1.0 }\nfrom = {}",
                       "key 'target[1].from': give one column"},
        BadCalibration{"test = \"ucs\"\nquantity = \"youngs",
                       "test = \"ucss\"\nquantity = \"youngs",
                       "key 'target[0].test': no [[test]] is named 'ucss'"},
        BadCalibration{"0.40556 * joints.jkn", "0.40556 * joints.jnk",
                       "key 'tie.joints.jks': 'joints.jnk' is neither a parameter"},
        BadCalibration{"runs = 60", "runs = 1",
                       "key 'budget.runs': 1 runs cannot afford one evaluation"}));
