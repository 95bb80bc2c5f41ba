// Contact-law behaviour and the law seam: one contact driven through its kinematics (A5 and A6
// are verification cases).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vorodec/laws/linear_elastic.hpp"
#include "vorodec/laws/mohr_coulomb.hpp"

using namespace vorodec::laws;

namespace {
constexpr double L = 1e-3, jkn = 1e13, jks = 4e12;
double tand(double deg) {
  return std::tan(deg * std::numbers::pi / 180.0);
}

MohrCoulomb::Props marble_joint(double dilation_deg) {
  return {jkn * L, jks * L, 14e6 * L, 24e6 * L, tand(25.5), tand(20.0), tand(dilation_deg)};
}
}  // namespace

TEST(MohrCoulomb, FailedJointCarriesNoTensionWhenPulledAgain) {
  const auto p = marble_joint(0.0);
  MohrCoulomb::State st{0.0, 0.0, true};
  EXPECT_EQ(MohrCoulomb::evaluate({1e-6, 1e-6, 0.0, L, 1e-7}, p, st).fn, 0.0);
  EXPECT_EQ(MohrCoulomb::evaluate({-1e-9, -1e-6, 0.0, L, 1e-7}, p, st).fn, p.kn * 1e-9);
}

TEST(MohrCoulomb, ForceIsContinuousInDisplacementBeforeFailure) {
  const auto p = marble_joint(0.0);
  MohrCoulomb::State st{0.0, 0.0, false};
  double prev = 0;
  for (int i = 0; i < 100; ++i) {
    const auto r = MohrCoulomb::evaluate({-i * 1e-9, -1e-9, 0.0, L, 1e-7}, p, st);
    EXPECT_NEAR(r.fn - prev, p.kn * 1e-9 * (i > 0), 1e-6);
    prev = r.fn;
  }
}

// The seam: a law registered by name, with its own parameters, state and no strength.
TEST(LawRegistry, LinearElasticIsASecondLawThatNeverFails) {
  ASSERT_NE(find_law("linear_elastic"), nullptr);
  ASSERT_NE(find_law("mohr_coulomb"), nullptr);
  EXPECT_EQ(find_law("no_such_law"), nullptr);
  LinearElastic::State st{0.0, 0.0};
  const LinearElastic::Props p{jkn * L, jks * L};
  const auto r = LinearElastic::evaluate({1e-3, 1e-3, 0.0, L, 1e-7}, p, st);  // huge tension
  EXPECT_EQ(r.event, ContactEvent::none);
  EXPECT_DOUBLE_EQ(r.fn, -jkn * L * 1e-3);
}

TEST(LawRegistry, EveryLawDocumentsUnitsOfItsParameters) {
  for (const auto& law : law_registry()) {
    EXPECT_FALSE(law.doc.empty());
    for (const auto& p : law.params) {
      EXPECT_FALSE(p.unit.empty()) << law.name << "." << p.key;
      EXPECT_FALSE(p.doc.empty()) << law.name << "." << p.key;
    }
  }
}

// A contact found during the run already overlapping starts unloaded: detection must not create
// strain energy. Its spring then works from that origin.
TEST(MohrCoulomb, ContactFoundOverlappingStartsWithZeroForce) {
  const MohrCoulomb::Props p{jkn * L, jks * L, 0.0, 0.0, 0.5, 0.5, 0.0};
  auto st = MohrCoulomb::initial_state({1, L, false, -2e-6});
  EXPECT_EQ(MohrCoulomb::evaluate({-2e-6, 0.0, 0.0, L, 1e-7}, p, st).fn, 0.0);
  EXPECT_DOUBLE_EQ(MohrCoulomb::evaluate({-3e-6, -1e-6, 0.0, L, 1e-7}, p, st).fn, jkn * L * 1e-6);
}
