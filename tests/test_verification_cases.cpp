// The analytic verification cases (A1-A8) as unit tests: each must meet its tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "case_assertions.hpp"
#include "cases.hpp"

using namespace vorodec::verification;

TEST(Verification, A1PolygonMassPropertiesAreExact) {
  EXPECT_TRUE(passes(a1_mass_properties()));
}
TEST(Verification, A2BlockAreasSumToOutlineAndAreReproducible) {
  EXPECT_TRUE(passes(a2_tessellation_area()));
}
TEST(Verification, A3BondedPairOscillatesWithTwoMassPeriod) {
  EXPECT_TRUE(passes(a3_bonded_pair_period()));
}
TEST(Verification, A3UndampedEnergyDoesNotDrift) {
  EXPECT_TRUE(passes(a3_bonded_pair_energy_drift()));
}
TEST(Verification, A4BlockSticksBelowFrictionAngle) {
  EXPECT_TRUE(passes(a4_incline(20)));
}
TEST(Verification, A4BlockSlidesWithCoulombAcceleration) {
  EXPECT_TRUE(passes(a4_incline(40)));
  EXPECT_TRUE(passes(a4_incline(50)));
}
TEST(Verification, A5ShearPeaksAtCohesionPlusFriction) {
  EXPECT_TRUE(passes(a5_direct_shear_peak()));
}
TEST(Verification, A5ShearDropsToResidualFriction) {
  EXPECT_TRUE(passes(a5_direct_shear_residual()));
}
TEST(Verification, A5DilationOpensBySlipTimesTanPsi) {
  EXPECT_TRUE(passes(a5_dilation()));
}
TEST(Verification, R2RoughJointPeaksAtBartonChoubeyStrength) {
  EXPECT_TRUE(passes(r2_peak_strength()));
}
TEST(Verification, R2RoughJointSoftensToResidualFriction) {
  EXPECT_TRUE(passes(r2_residual_strength()));
}
TEST(Verification, R2RoughJointDilatesAtHalfItsRoughnessAngle) {
  EXPECT_TRUE(passes(r2_dilation()));
}
TEST(Verification, R2RoughJointClosesOnTheBandisHyperbola) {
  EXPECT_TRUE(passes(r2_normal_closure()));
}
TEST(Verification, R1KirschHoleWallClosesByTheElasticSolution) {
  // Zone size 0.1 a at the wall: the displacement within the target; the stresses reach it at
  // 0.025 a (verification --rock-only) and are held here to this rung's 4.2 and 5.1 %.
  const auto rows = r1_kirsch(0.1);
  EXPECT_TRUE(passes(rows[2]));
  EXPECT_LT(rows[0].error, 0.05);
  EXPECT_LT(rows[1].error, 0.06);
}
TEST(Verification, R5DiggingTheHoleOutOfTheLoadedPlateGivesKirsch) {
  // The same rung as R1's test: measured 4.2 %, 5.1 % and 0.5 %.
  const auto rows = r1_kirsch(0.1, true);
  EXPECT_TRUE(passes(rows[2]));
  EXPECT_LT(rows[0].error, 0.05);
  EXPECT_LT(rows[1].error, 0.06);
}
TEST(Verification, R3RoofWedgeFallsBelowItsLimitFrictionAndStaysAbove) {
  for (const auto& r : r3_roof_wedge()) EXPECT_TRUE(passes(r));
}
TEST(Verification, R4InSituStartCarriesTheFieldThroughEveryCut) {
  for (const auto& r : r4_in_situ_start(VORODEC_SOURCE_DIR))
    EXPECT_TRUE(passes(r)) << r.name << ": " << r.measured << " against " << r.expected;
}
TEST(Verification, J0JointSeparatesBlockPairsAlongItsWholeChord) {
  for (const double dip : {0.0, 30.0, 60.0, 90.0}) EXPECT_TRUE(passes(j0_joint_length(dip)));
}
TEST(Verification, A6TensionBreaksAtStrengthTimesLength) {
  EXPECT_TRUE(passes(a6_direct_tension()));
}
TEST(Verification, A7WeibullSamplesFollowTheCdf) {
  EXPECT_TRUE(passes(a7_weibull_ks()));
}
TEST(Verification, A7WeibullMeanIsA0) {
  EXPECT_TRUE(passes(a7_weibull_mean()));
}
TEST(Verification, A8LocalDampingRemovesAnalyticEnergyFraction) {
  EXPECT_TRUE(passes(a8_local_damping()));
}
TEST(Verification, A10BurgersContactFollowsTheAnalyticCreepCurveNormalAndShear) {
  EXPECT_TRUE(passes(a10_burgers_creep(false)));
  EXPECT_TRUE(passes(a10_burgers_creep(true)));
}
TEST(Verification, A10BurgersCreepIsSecondOrderFromTheConsistentStartFirstOrderFromZero) {
  const std::vector<Ladder> ladders = a10_ladders();
  ASSERT_EQ(ladders.size(), 2u);
  EXPECT_NEAR(ladders[0].order(), 2.0, 0.2);
  EXPECT_NEAR(ladders[1].order(), 1.0, 0.2);
}

TEST(Verification, G1MineralAreaFractionsMatchTheRequestWithinOneGrain) {
  for (const auto& r : g1_mineral_fractions(0.01, 1.52e-3)) EXPECT_TRUE(passes(r));
}

TEST(Verification, A11CorrodingContactFailsAtTheQuadratureTimeBothLayers) {
  for (const bool bonded_length : {false, true})
    for (const double s : {0.5, 0.7, 0.9}) {
      const CaseResult r = a11_stress_corrosion(bonded_length, s, 4);
      EXPECT_TRUE(passes(r)) << r.name << " s " << s << ": " << r.measured << " vs " << r.expected;
    }
}

TEST(Verification, A11FrozenRateEstimateOverestimatesTheFailureTimeAtAboutFirstOrderInNc) {
  const Ladder l = a11_frozen_ladder();
  for (const auto& r : l.rungs) EXPECT_GT(r.value, l.reference_value) << "1/n_c " << r.parameter;
  EXPECT_GT(l.order(), 0.6);
  EXPECT_LT(l.order(), 1.2);
}

TEST(Verification, A11NoDegradationBelowTheActivationLevel) {
  EXPECT_TRUE(std::isinf(a11_stepped(false, 0.3, 4, false)));
  EXPECT_TRUE(passes(a11_stress_corrosion(false, 0.3, 4)));
}

TEST(Verification, A9PWaveInARowOfBlocksTravelsAtSqrtJknDOverRho) {
  for (const auto& r : a9_row_of_blocks()) {
    if (!r.informational) {
      EXPECT_TRUE(passes(r));
    }
  }
}
TEST(Verification, A9QuietEndReflectsAlmostNothingAndAFreeEndEverything) {
  for (const auto& r : quiet_boundary_absorption()) {
    EXPECT_TRUE(passes(r));
  }
}
TEST(Verification, A9PWaveInAVoronoiBarTravelsAtItsStaticModulusSpeed) {
  for (const auto& r : a9_voronoi_bar()) {
    EXPECT_TRUE(passes(r));
  }
}
TEST(Verification, A9UndampedRowWithQuietEndsStaysBounded) {
  EXPECT_TRUE(passes(quiet_row_long_run(50000)));  // the report runs 1e6 steps
}
