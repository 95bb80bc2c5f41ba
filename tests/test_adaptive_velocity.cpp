// Adaptive platen speed (stage key adaptive_velocity): the controller speeds up while the specimen
// is near equilibrium and slows down when it is not, the model file reads it, and a small run
// reaches its peak in fewer steps than the fixed minimum speed with nearly the same peak.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "run_support.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/loading/stage_control.hpp"

namespace fs = std::filesystem;
using namespace vorodec;
using vorodec::testing::base_dir;
using vorodec::testing::out_dir;
using vorodec::testing::read_csv;
using vorodec::testing::run_vorodec;

namespace {

constexpr double dt = 1e-6;  // s

loading::Stage adaptive_stage() {
  loading::Stage st;
  st.platen_velocity = 2e-3;
  st.end.axial_strain = 0.01;
  st.adaptive = {true, 1e-3, 1e-3, 1e-2, 100, 1.25};
  return st;
}

// The speed after `updates` control updates at a constant ratio, at the end of the last move.
double speed_after(loading::StageControl& c, double ratio, int updates) {
  double ts = 0;
  for (int i = 0; i < updates; ++i, ts += 100 * dt) c.adapt(ratio, ts, dt);
  return c.platen_velocity(ts, 0, 0, dt, 0);
}

const std::string small_model = std::string(VORODEC_SOURCE_DIR) + "/tests/models/e2e_small.toml";

// e2e_small loaded at 2 mm/s, or adaptively between 2 and 40 mm/s.
std::string load_stage(bool adaptive) {
  return std::string(
             " --set 'stage[0]={name=\"load\",platen_velocity=2e-3,ramp_time=2e-4,"
             "end_post_peak_fraction=0.6,end_axial_strain=0.02") +
         (adaptive ? ",adaptive_velocity={target_ratio=1e-3,min_velocity=2e-3,"
                     "max_velocity=4e-2,interval_steps=200}}'"
                   : "}'");
}

// Step of the highest axial stress (column 3) in a history.
double steps_to_peak(const std::vector<std::vector<double>>& rows, double* peak) {
  const auto it = std::max_element(rows.begin(), rows.end(),
                                   [](const auto& a, const auto& b) { return a[3] < b[3]; });
  *peak = (*it)[3];
  return (*it)[0];
}

}  // namespace

TEST(AdaptiveVelocity, RaisesTheSpeedWhileTheRatioIsBelowTargetUpToTheMaximum) {
  const loading::Stage st = adaptive_stage();
  loading::StageControl c(st, 0.0, 0.0, 0.0);
  c.adapt(1e-5, 0.0, dt);
  // The change is spread over the interval: halfway there after half of it.
  EXPECT_DOUBLE_EQ(c.platen_velocity(0.0, 0, 0, dt, 0), 2e-3);
  EXPECT_NEAR(c.platen_velocity(50 * dt, 0, 0, dt, 0), 2.25e-3, 1e-12);
  EXPECT_NEAR(c.platen_velocity(100 * dt, 0, 0, dt, 0), 2.5e-3, 1e-12);
  loading::StageControl d(st, 0.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(speed_after(d, 1e-5, 20), 1e-2);
}

TEST(AdaptiveVelocity, LowersTheSpeedWhileTheRatioIsAboveTargetDownToTheMinimum) {
  const loading::Stage st = adaptive_stage();
  loading::StageControl c(st, 0.0, 0.0, 0.0);
  EXPECT_NEAR(speed_after(c, 0.1, 1), 1.6e-3, 1e-12);
  loading::StageControl d(st, 0.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(speed_after(d, 0.1, 20), 1e-3);
}

TEST(AdaptiveVelocity, StepsBySquareRootOfTheRatioNearTheTargetAndSlowsOnNaN) {
  const loading::Stage st = adaptive_stage();
  loading::StageControl near(st, 0.0, 0.0, 0.0);
  EXPECT_NEAR(speed_after(near, 1.21e-3, 1), 2e-3 / 1.1, 1e-12);
  loading::StageControl nan(st, 0.0, 0.0, 0.0);
  EXPECT_NEAR(speed_after(nan, std::nan(""), 1), 1.6e-3, 1e-12);
  loading::StageControl zero(st, 0.0, 0.0, 0.0);
  EXPECT_NEAR(speed_after(zero, 0.0, 1), 2.5e-3, 1e-12);
}

TEST(AdaptiveVelocity, ModelFileReadsTheTableWithItsDefaults) {
  const fs::path dir = fs::temp_directory_path() / ("vorodec_adaptive_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "m.toml")
      << "base = \"" << small_model
      << "\"\n[[stage]]\nplaten_velocity = 5e-3\nend_axial_strain = 0.01\n"
         "adaptive_velocity = { target_ratio = 5e-4, min_velocity = "
         "1e-3, max_velocity = 2e-2 }\n";
  const io::ModelConfig cfg = run::read_model_file(dir / "m.toml");
  const loading::AdaptiveVelocity& a = cfg.load_path.stages.at(0).adaptive;
  EXPECT_TRUE(a.enabled);
  EXPECT_EQ(a.target_ratio, 5e-4);
  EXPECT_EQ(a.min_velocity, 1e-3);
  EXPECT_EQ(a.max_velocity, 2e-2);
  EXPECT_EQ(a.interval_steps, 500);
  EXPECT_EQ(a.max_change, 1.25);
  EXPECT_FALSE(run::read_model_file(small_model).load_path.stages.at(0).adaptive.enabled);
}

// One adaptive run of e2e_small and the same at its fixed minimum speed: peak in fewer steps,
// peak stress within 5 % (this 170-block specimen's peak scatters by a few % with any change of
// path), the history shows the speed and ratio, and two threads give the same run bit for bit.
TEST(AdaptiveVelocity, SmallRunReachesItsPeakInFewerStepsThanTheFixedMinimumSpeed) {
  const fs::path fixed = out_dir("fixed_min"), adaptive = out_dir("adaptive"),
                 two = out_dir("adaptive_two");
  const std::string run = "run " + small_model + " --no-vtk";
  ASSERT_EQ(run_vorodec(run + " --threads 1 --out " + fixed.string() + load_stage(false)), 0);
  ASSERT_EQ(run_vorodec(run + " --threads 1 --out " + adaptive.string() + load_stage(true)), 0);
  ASSERT_EQ(run_vorodec(run + " --threads 2 --out " + two.string() + load_stage(true)), 0);
  const auto f = read_csv(fixed / "history.csv"), a = read_csv(adaptive / "history.csv");
  double peak_f = 0, peak_a = 0;
  const double steps_f = steps_to_peak(f, &peak_f), steps_a = steps_to_peak(a, &peak_a);
  EXPECT_LT(steps_a, 0.7 * steps_f);
  EXPECT_NEAR(peak_a / peak_f, 1.0, 0.05);
  // Columns 17 and 18: platen_velocity and unbalanced_force_ratio.
  double fastest = 0;
  for (const auto& row : a) {
    ASSERT_EQ(row.size(), 19u);
    fastest = std::max(fastest, row[17]);
    EXPECT_GE(row[18], 0.0);
  }
  EXPECT_GT(fastest, 4e-3);
  EXPECT_LE(fastest, 4e-2);
  const auto b = read_csv(two / "history.csv");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "row " << i;
}
