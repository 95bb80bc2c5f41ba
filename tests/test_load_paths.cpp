// Load paths: stage control (servo directions, end on stress, stall), cyclic blocks, per-cycle
// measures on loops with known areas, failure stages, elastic constants, and cyclic / tension /
// Brazilian runs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "vorodec/loading/stage_control.hpp"
#include "vorodec/measure/cycles.hpp"
#include "vorodec/measure/failure_stages.hpp"
#include "vorodec/measure/specimen.hpp"

namespace fs = std::filesystem;
using namespace vorodec;

namespace {

loading::Stage unloading(double rate, double end_stress) {
  loading::Stage st;
  st.control = loading::Control::stress_rate;
  st.stress_rate = rate;
  st.platen_velocity = 0.05;
  st.end.axial_stress = end_stress;
  return st;
}

}  // namespace

TEST(StageControl, StressRateTargetFollowsTheRampAndStopsAtTheEndStress) {
  const loading::Stage st = unloading(-1e9, 2e6);
  const loading::StageControl c(st, 0.0, 10e6, 0.0);
  EXPECT_DOUBLE_EQ(c.target(0.0), 10e6);
  EXPECT_DOUBLE_EQ(c.target(3e-3), 7e6);
  EXPECT_DOUBLE_EQ(c.target(1.0), 2e6);
}

TEST(StageControl, UnloadingServoNeverPushesThePlatenBackUp) {
  const loading::Stage st = unloading(-1e9, 0.0);
  const loading::StageControl c(st, 0.0, 10e6, 0.0);
  // Stress far below the target (a failing specimen sheds stress): the platen waits.
  EXPECT_EQ(c.platen_velocity(1e-3, 1e6, 1e9, 1e-7, 0.05), 0.0);
  // Stress above the target: the platen retracts, no faster than the cap.
  const double v = c.platen_velocity(1e-3, 20e6, 1e9, 1e-7, 0.05);
  EXPECT_LT(v, 0.0);
  EXPECT_GE(v, -0.05);
}

TEST(StageControl, StageEndsWhenStressCrossesItsEndStressInEitherDirection) {
  loading::Stage up;
  up.platen_velocity = 0.01;
  up.end.axial_stress = 30e6;
  loading::StageControl rising(up, 0.0, 0.0, 0.0);
  EXPECT_EQ(rising.judge({0.0, 29e6, 1e-3, false}), loading::StageOutcome::running);
  EXPECT_EQ(rising.judge({0.0, 30e6, 1e-3, false}), loading::StageOutcome::done);
  const loading::Stage down = unloading(-1e9, 1e6);
  loading::StageControl falling(down, 0.0, 30e6, 0.0);
  EXPECT_EQ(falling.judge({0.0, 2e6, 1e-3, false}), loading::StageOutcome::running);
  EXPECT_EQ(falling.judge({0.0, 1e6, 1e-3, false}), loading::StageOutcome::done);
}

TEST(StageControl, LoadingThatPeaksBelowItsTargetStalls) {
  loading::Stage up;
  up.platen_velocity = 0.01;
  up.end.axial_stress = 80e6;
  loading::StageControl c(up, 0.0, 0.0, 0.0);
  const double rows[] = {40e6, 50e6, 55e6, 54e6, 53e6};
  for (double s : rows) EXPECT_EQ(c.judge({0.0, s, 0.0, true}), loading::StageOutcome::running);
  EXPECT_EQ(c.judge({0.0, 52e6, 0.0, true}), loading::StageOutcome::stalled);
}

TEST(StageControl, PulledSpecimenEndsAfterItsTensilePeak) {
  loading::Stage pull;
  pull.platen_velocity = -0.01;
  pull.end.post_peak_fraction = 0.5;
  loading::StageControl c(pull, 0.0, 0.0, 0.0);
  for (double s : {-2e6, -5e6, -6e6, -5e6, -4e6, -3.5e6})
    EXPECT_EQ(c.judge({0.0, s, 0.0, true}), loading::StageOutcome::running);
  EXPECT_EQ(c.judge({0.0, -2.9e6, 0.0, true}), loading::StageOutcome::done);
}

TEST(CyclicBlock, ExpandsIntoLoadingAndUnloadingStagesThatResumeAfterTheBlock) {
  std::vector<loading::Stage> stages(1);
  loading::CyclicBlock b;
  b.upper_stresses = {10e6, 20e6, 30e6};
  b.lower_stress = 1e6;
  b.loading_velocity = 5e-3;
  b.unloading_rate = 2e9;
  loading::append_cycles(b, stages);
  ASSERT_EQ(stages.size(), 7u);
  for (int k = 0; k < 3; ++k) {
    const loading::Stage& load = stages[1 + 2 * k];
    const loading::Stage& unload = stages[2 + 2 * k];
    EXPECT_EQ(load.phase, loading::CyclePhase::loading);
    EXPECT_EQ(load.cycle, k + 1);
    EXPECT_DOUBLE_EQ(load.end.axial_stress, b.upper_stresses[static_cast<std::size_t>(k)]);
    EXPECT_EQ(load.platen_velocity, 5e-3);
    EXPECT_EQ(unload.control, loading::Control::stress_rate);
    EXPECT_DOUBLE_EQ(unload.stress_rate, -2e9);
    EXPECT_DOUBLE_EQ(unload.end.axial_stress, 1e6);
    EXPECT_EQ(load.block_end, 7);
    EXPECT_EQ(unload.block_end, 7);
  }
}

TEST(CycleMeasures, LoopWithKnownAreasGivesExactWorksModulusAndResidualStrain) {
  // Loading 0 -> (2e-3, 40 MPa) linearly, unloading linearly to (5e-4, 0): W_tol = 40e3 J/m3,
  // W_e = 30e3 J/m3, W_dis = 10e3 J/m3, secant 20 GPa, residual strain 5e-4.
  std::vector<measure::HistoryPoint> rows;
  for (int i = 0; i <= 10; ++i) rows.push_back({2e-4 * i, 4e6 * i, -0.25 * 2e-4 * i, 0});
  for (int i = 0; i <= 10; ++i) rows.push_back({2e-3 - 1.5e-4 * i, 40e6 - 4e6 * i, -5e-4, 1});
  std::vector<loading::Stage> stages(2);
  stages[0].phase = loading::CyclePhase::loading;
  stages[0].cycle = 1;
  stages[0].end.axial_stress = 40e6;
  stages[1].phase = loading::CyclePhase::unloading;
  const auto m = measure::cycle_measures(rows, stages, {false, false});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR(m[0].input_work, 40e3, 1e-9 * 40e3);
  EXPECT_NEAR(m[0].recovered_work, 30e3, 1e-9 * 30e3);
  EXPECT_NEAR(m[0].dissipated_work, 10e3, 1e-9 * 10e3);
  EXPECT_NEAR(m[0].secant_modulus, 20e9, 1e-9 * 20e9);
  EXPECT_NEAR(m[0].poisson_ratio, 0.25, 1e-12);
  EXPECT_NEAR(m[0].residual_strain, 5e-4, 1e-15);
  EXPECT_DOUBLE_EQ(m[0].upper_reached, 40e6);
}

TEST(FailureStages, InitiationAtFirstFailureAndAccelerationWhereTheRateDoubles) {
  // Failure rate zero up to strain 1e-3, then growing at 1 per unit strain, then at 10 per unit
  // strain from 2e-3; peak at 3e-3.
  std::vector<double> e, s, r;
  for (int i = 0; i <= 300; ++i) {
    const double x = 1e-5 * i;
    e.push_back(x);
    s.push_back(x <= 3e-3 ? 1e10 * x : 3e7 - 1e10 * (x - 3e-3));
    r.push_back(x <= 1e-3 ? 0.0 : x <= 2e-3 ? (x - 1e-3) : 1e-3 + 10.0 * (x - 2e-3));
  }
  const auto f = measure::failure_stages(e, s, r);
  ASSERT_TRUE(f.valid);
  EXPECT_NEAR(f.crack_initiation_stress, 1.01e7, 1.0);
  EXPECT_NEAR(f.peak_stress, 3e7, 1.0);
  EXPECT_GT(f.accelerating_stress, 2.0e7);
  EXPECT_LT(f.accelerating_stress, 2.15e7);
}

TEST(ElasticConstants, InitialRatioFitsTheLinearRangeAndTheTangentOneTheDilatingMiddle) {
  // E 30 GPa to the peak at 1.5e-3; lateral strain -0.18 e up to 35 % of peak (its linear range),
  // then -0.25 e beyond: the 10-30 % fit gives 0.18, the 40-60 % fit 0.25.
  std::vector<double> e, s, l;
  const double knee = 0.35 * 1.5e-3;
  for (int i = 0; i <= 200; ++i) {
    const double x = 1e-5 * i;
    e.push_back(x);
    s.push_back(x <= 1.5e-3 ? 3e10 * x : 4.5e7 - 3e10 * (x - 1.5e-3));
    l.push_back(x <= knee ? -0.18 * x : -0.18 * knee - 0.25 * (x - knee));
  }
  const auto c = measure::elastic_constants(e, s, l);
  ASSERT_TRUE(c.valid);
  EXPECT_NEAR(c.youngs_modulus, 3e10, 1.0);
  EXPECT_NEAR(c.poisson_ratio, 0.25, 1e-12);
  EXPECT_NEAR(c.initial_poisson_ratio, 0.18, 1e-12);
}

TEST(StageControl, ReloadingThatDipsWhileItsVelocityRampsUpDoesNotStall) {
  loading::Stage up;
  up.platen_velocity = 0.01;
  up.ramp_time = 1e-3;
  up.end.axial_stress = 30e6;
  loading::StageControl c(up, -0.01, 20e3, 0.0);  // after an unloading: platen still retracting
  for (double s : {10e3, 0.0, 0.0, 0.0, 0.0, 5e3})
    EXPECT_EQ(c.judge({0.0, s, 0.0, true}), loading::StageOutcome::running);
}

TEST(StageControl, ConfinedSpecimenDropBelowTheConfinementIsNoPeak) {
  loading::Stage load;
  load.platen_velocity = 0.01;
  load.end.post_peak_fraction = 0.5;
  loading::StageControl c(load, 0.0, 0.0, 0.0);
  // The lateral squeeze of a 20 MPa step lifts the axial stress and lets it fall back.
  for (double s : {3e6, 6e6, 4e6, 2e6, 1e6, 0.5e6, 10e6, 40e6, 60e6, 50e6, 40e6, 31e6})
    EXPECT_EQ(c.judge({0.0, s, 0.0, true, 20e6}), loading::StageOutcome::running) << s;
  EXPECT_EQ(c.judge({0.0, 29e6, 0.0, true, 20e6}), loading::StageOutcome::done);
}
