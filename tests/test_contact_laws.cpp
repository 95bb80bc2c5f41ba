// Contact-law behaviour and the law seam: one contact driven through its kinematics (A5 and A6
// are verification cases).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vorodec/laws/burgers.hpp"
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
  auto st = MohrCoulomb::initial_state(p, {1, L, false, -2e-6});
  EXPECT_EQ(MohrCoulomb::evaluate({-2e-6, 0.0, 0.0, L, 1e-7}, p, st).fn, 0.0);
  EXPECT_DOUBLE_EQ(MohrCoulomb::evaluate({-3e-6, -1e-6, 0.0, L, 1e-7}, p, st).fn, jkn * L * 1e-6);
}

namespace {
// A Burger's contact (per contact: the length is in the values) with a Coulomb slider.
Burgers::Props burgers_joint(double tension, double cohesion, bool carries_tension) {
  const BurgersChain e{2e10, 2e15, 5e10, 5e14};
  return {e, e, {tension, cohesion, tand(30.0), tand(30.0)}, carries_tension ? 1.0 : 0.0};
}
}  // namespace

TEST(Burgers, WorkOnTheContactIsItsSpringEnergyPlusDashpotWorkEveryStep) {
  const auto p = burgers_joint(1e300, 1e300, true);
  Burgers::State st{0, 0, 0, 0, 0, 0, false};
  double gap = 0, fn = 0, fs = 0, work = 0, dashpots = 0;
  for (int i = 0; i < 2000; ++i) {
    const double dn = -1e-9 * std::sin(0.01 * i) - 2e-10, ds = 3e-10 * std::cos(0.013 * i);
    double w = 0;
    const auto r = Burgers::evaluate({gap + dn, dn, ds, L, 50.0}, p, st, w);
    work += -0.5 * ((fn + r.fn) * dn + (fs + r.fs) * ds);
    dashpots += w;
    gap += dn;
    fn = r.fn;
    fs = r.fs;
  }
  EXPECT_GT(dashpots, 0.0);
  EXPECT_NEAR(work, Burgers::strain_energy(p, st, fn, fs) + dashpots, 1e-9 * std::abs(work));
}

TEST(Burgers, SliderCapsTheShearForceAtCohesionPlusFrictionThenBreaks) {
  const auto p = burgers_joint(1e300, 5.0, true);
  Burgers::State st{0, 0, 0, 0, 0, 0, false};
  const double gap = -1e-9;  // compressed: fn about Km x 1e-9 = 20 N
  double peak = 0;
  ContactEvent first = ContactEvent::none;
  for (int i = 0; i < 400 && first == ContactEvent::none; ++i) {
    double w = 0;
    const auto r = Burgers::evaluate({gap, i == 0 ? gap : 0.0, -1e-11, L, 1e-6}, p, st, w);
    peak = std::max(peak, r.fs);
    first = r.event;
    if (first != ContactEvent::none) {
      EXPECT_NEAR(r.fs, r.fn * tand(30.0), 1e-9);
    }
  }
  EXPECT_EQ(first, ContactEvent::shear_failure);
  EXPECT_TRUE(st.broken);
  EXPECT_LE(peak, 5.0 + 20.0 * tand(30.0) + 1e-6);
}

TEST(Burgers, OpensUnderTensionUnlessItCarriesTension) {
  for (const bool carries : {false, true}) {
    const auto p = burgers_joint(1.0, 1.0, carries);
    Burgers::State st{0, 0, 0, 0, 0, 0, false};
    double w = 0;
    const auto r = Burgers::evaluate({1e-9, 1e-9, 0.0, L, 1e-6}, p, st, w);  // pulled: ~-20 N
    if (carries) {
      EXPECT_LT(r.fn, -1.0);
      EXPECT_EQ(r.event, ContactEvent::none);
    } else {
      EXPECT_EQ(r.fn, 0.0);
      EXPECT_EQ(r.event, ContactEvent::tensile_failure);
    }
  }
}

TEST(Burgers, AnOpenContactClosesWhereItsMaxwellSpringIsUnloaded) {
  const auto p = burgers_joint(0.0, 0.0, false);
  Burgers::State st{0, 0, 0, 0, 0, 0, true};
  double w = 0;
  // Pressed for a long step, the Maxwell dashpot flows: the unloaded gap moves by umn.
  Burgers::evaluate({-1e-9, -1e-9, 0.0, L, 1e3}, p, st, w);
  const double umn = st.umn;
  EXPECT_GT(umn, 0.0);
  const auto open = Burgers::evaluate({1e-9, 2e-9, 0.0, L, 1e-9}, p, st, w);
  EXPECT_EQ(open.fn, 0.0);
  // Closed again to just past the flowed dashpot (and the relaxed Kelvin element): compression.
  const auto closed = Burgers::evaluate({-(st.umn + st.ukn) - 1e-12, 0.0, 0.0, L, 1e-9}, p, st, w);
  EXPECT_GT(closed.fn, 0.0);
}

TEST(Burgers, AContactWithoutTensionOrCohesionHasNoBondToLose) {
  const auto frictional = burgers_joint(0.0, 0.0, false);
  const auto bonded = burgers_joint(1.0, 0.0, false);
  const NewContact c{1, L, true, 0.0};
  EXPECT_TRUE(Burgers::initial_state(frictional, c).broken);
  EXPECT_FALSE(Burgers::initial_state(bonded, c).broken);
}
