// A5, A6 and the law seam: one contact driven through its kinematics, no solver.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vorodec/laws/linear_elastic.hpp"
#include "vorodec/laws/mohr_coulomb.hpp"

using namespace vorodec::laws;

namespace {
constexpr double L = 1e-3, jkn = 1e13, jks = 4e12;
double tand(double deg) { return std::tan(deg * std::numbers::pi / 180.0); }

MohrCoulomb::Props marble_joint(double dilation_deg) {
  return {jkn * L, jks * L, 14e6 * L, 24e6 * L, tand(25.5), tand(20.0), tand(dilation_deg)};
}
}  // namespace

// A5: direct shear of one bonded joint under constant normal stress.
TEST(MohrCoulomb, DirectShearPeaksAtCohesionPlusFrictionThenDropsToResidual) {
  const double sn = 10e6;
  const auto p = marble_joint(0.0);
  MohrCoulomb::State st{0.0, 0.0, false};
  const double gap = -sn * L / p.kn;
  double peak = 0, last = 0;
  ContactEvent failure = ContactEvent::none;
  for (int i = 0; i < 4000; ++i) {
    const auto r = MohrCoulomb::evaluate({gap, 0.0, -1e-8, L, 1e-7}, p, st);
    peak = std::max(peak, std::abs(r.fs));
    last = std::abs(r.fs);
    if (r.event == ContactEvent::shear_failure) failure = r.event;
    EXPECT_DOUBLE_EQ(r.fn, sn * L);
  }
  EXPECT_EQ(failure, ContactEvent::shear_failure);
  const double expected_peak = (24e6 + sn * tand(25.5)) * L;
  // The peak is reached between two increments: within one increment's force jump.
  EXPECT_NEAR(peak, expected_peak, p.ks * 1e-8);
  EXPECT_NEAR(peak / expected_peak, 1.0, 0.01);
  EXPECT_NEAR(last, sn * tand(20.0) * L, 1e-9 * last);
}

// A5, dilation: under constant normal stress the joint opens by slip x tan(psi).
TEST(MohrCoulomb, DilationOpensTheJointBySlipTimesTanPsi) {
  const double sn = 5e6, psi = 18.0;
  const auto p = marble_joint(psi);
  MohrCoulomb::State st{0.0, 0.0, true};  // already failed: purely frictional, dilating
  double gap = -sn * L / p.kn;
  const double gap0 = gap;
  double slip = 0;
  for (int i = 0; i < 2000; ++i) {
    const double fs_before = st.fs;
    const auto r = MohrCoulomb::evaluate({gap, 0.0, -1e-7, L, 1e-7}, p, st);
    if (r.event == ContactEvent::slip) slip += 1e-7 - (st.fs - fs_before) / p.ks;
    gap = st.u_dil - sn * L / p.kn;  // a normal-stress servo: the joint opens to keep Fn
  }
  ASSERT_GT(slip, 1e-4);
  EXPECT_NEAR((gap - gap0) / slip, tand(psi), 1e-9);
}

// A6: direct tension of one bonded joint.
TEST(MohrCoulomb, DirectTensionBreaksAtTensileStrengthTimesLength) {
  const auto p = marble_joint(0.0);
  MohrCoulomb::State st{0.0, 0.0, false};
  const double du = 1e-10;
  double max_tension = 0;
  for (int i = 1; i < 100000; ++i) {
    const auto r = MohrCoulomb::evaluate({i * du, du, 0.0, L, 1e-7}, p, st);
    if (r.event == ContactEvent::tensile_failure) {
      EXPECT_EQ(r.fn, 0.0);
      break;
    }
    max_tension = std::max(max_tension, -r.fn);
  }
  EXPECT_TRUE(st.broken);
  EXPECT_NEAR(max_tension, 14e6 * L, p.kn * du);
  // A failed joint carries no tension when pulled again.
  EXPECT_EQ(MohrCoulomb::evaluate({1e-6, 0.0, 0.0, L, 1e-7}, p, st).fn, 0.0);
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
  LinearElastic::State st{0.0};
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
