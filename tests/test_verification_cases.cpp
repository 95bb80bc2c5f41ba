// The analytic verification cases (A1-A8) as unit tests: each must meet its tolerance.
#include <gtest/gtest.h>

#include "cases.hpp"

using namespace vorodec::verification;

namespace {
void expect_pass(const CaseResult& r) {
  EXPECT_LE(r.error, r.tolerance) << r.id << " " << r.name << ": expected " << r.expected
                                  << ", measured " << r.measured << " (" << r.reference << ")";
}
}  // namespace

TEST(Verification, A1PolygonMassPropertiesAreExact) { expect_pass(a1_mass_properties()); }
TEST(Verification, A2BlockAreasSumToOutlineAndAreReproducible) {
  expect_pass(a2_tessellation_area());
}
TEST(Verification, A3BondedPairOscillatesWithTwoMassPeriod) {
  expect_pass(a3_bonded_pair_period());
}
TEST(Verification, A3UndampedEnergyDoesNotDrift) { expect_pass(a3_bonded_pair_energy_drift()); }
TEST(Verification, A4BlockSticksBelowFrictionAngle) { expect_pass(a4_incline(20)); }
TEST(Verification, A4BlockSlidesWithCoulombAcceleration) {
  expect_pass(a4_incline(40));
  expect_pass(a4_incline(50));
}
TEST(Verification, A5ShearPeaksAtCohesionPlusFriction) { expect_pass(a5_direct_shear_peak()); }
TEST(Verification, A5ShearDropsToResidualFriction) { expect_pass(a5_direct_shear_residual()); }
TEST(Verification, A5DilationOpensBySlipTimesTanPsi) { expect_pass(a5_dilation()); }
TEST(Verification, A6TensionBreaksAtStrengthTimesLength) { expect_pass(a6_direct_tension()); }
TEST(Verification, A7WeibullSamplesFollowTheCdf) { expect_pass(a7_weibull_ks()); }
TEST(Verification, A7WeibullMeanIsA0) { expect_pass(a7_weibull_mean()); }
TEST(Verification, A8LocalDampingRemovesAnalyticEnergyFraction) { expect_pass(a8_local_damping()); }
