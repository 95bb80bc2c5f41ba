// Stress corrosion (docs/theory.md §14.2): the beam section vorodec maps a sub-block joint onto,
// and the corrosion stage end to end (A11 is a verification case).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "run_support.hpp"
#include "scenes.hpp"
#include "vorodec/laws/stress_corrosion.hpp"
#include "vorodec/model/build.hpp"
#include "vorodec/model/contact_geometry.hpp"

using namespace vorodec;

namespace {
constexpr double a = 0.01, jkn = 1e13, jks = 4e12;  // m, Pa/m

// The joint's contacts as the corrosion stage reads them: forces and points along the joint.
std::vector<laws::PairContact> joint_contacts(model::Model& m, std::vector<std::size_t>& index) {
  std::vector<laws::PairContact> out;
  index.clear();
  model::Point tangent{0, 0};
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    model::Contact& c = m.contacts[i];
    const model::ContactFrame f = model::contact_frame(m.blocks.corners(), c);
    if (out.empty()) tangent = {-f.n.y, f.n.x};
    out.push_back({c.fn, c.fs, dot(f.point, tangent), c.length});
    index.push_back(i);
  }
  return out;
}
}  // namespace

TEST(StressCorrosion, BondSectionStressesAreThePapersBeamFormulas) {
  const laws::BondSection s{2e3, -300.0, 0.4, 2e-3};  // N, N, N m, m
  EXPECT_DOUBLE_EQ(laws::bond_tension(s), -2e3 / 2e-3 + 6.0 * 0.4 / (2e-3 * 2e-3));
  EXPECT_DOUBLE_EQ(laws::bond_shear(s), 300.0 / 2e-3);
  // D_min: forces held, the section at D_min is exactly at its strength (tension here).
  const laws::BondStrength b{1.0e9, 1e12, 0.5};
  const laws::BondedLength law{25.8, 0.0, 0.01};
  const double d_min = laws::min_bonded_length(law, s, b, 2e-3);
  laws::BondSection at = s;
  at.d = d_min;
  EXPECT_NEAR(laws::bond_tension(at), b.tension, 1e-9 * b.tension);
  EXPECT_LT(d_min, s.d);
  // Shear-limited: |Fs| = xi D c + Fn tan(phi).
  const laws::BondStrength weak_shear{1e12, 1.0e6, 0.5};
  at = {2e3, 2500.0, 0.0, 2e-3};
  at.d = laws::min_bonded_length(law, at, weak_shear, 2e-3);
  EXPECT_NEAR(at.d, (2500.0 - 2e3 * 0.5) / 1.0e6, 1e-15);
  EXPECT_NEAR(laws::bond_shear(at), weak_shear.cohesion + at.fn / at.d * weak_shear.tan_phi, 1e-3);
}

// One joint between two rigid squares, pressed, sheared and bent through the real solver: the
// pair's forces are the section's (Fn = jkn D delta, Fs = jks D u, M = jkn J theta with J the
// pair's second moment of length), and shrinking the bonded length to xi D at unchanged
// displacements leaves the joint with xi Fn, xi Fs and xi^3 M.
TEST(StressCorrosion, ShrinkingABentJointScalesItsForceByXiAndItsMomentByXiCubed) {
  model::Model m;
  m.rounding_length = 0.01 * a;
  model::add_block(m, verification::square(0, 0, a), 2600, model::Group::specimen);
  model::add_block(m, verification::square(0, a, a), 2600, model::Group::specimen);
  solver::SolverSettings settings;
  auto solver = verification::make_solver(m, "mohr_coulomb",
                                          verification::params({{"jkn", jkn},
                                                                {"jks", jks},
                                                                {"tension", 1e10},
                                                                {"cohesion", 1e10},
                                                                {"friction", 30.0},
                                                                {"dilation", 0.0}}),
                                          settings);
  m.blocks.prescribed.assign(2, 1);
  const double delta = 1e-7, theta = 1e-5, u = 2e-8, dt = solver->dt();
  // Block 1 turns by theta about the joint's centre, moves down by delta and sideways by u.
  m.blocks.vx[1] = (-theta * 0.5 * a + u) / dt;
  m.blocks.vy[1] = -delta / dt;
  m.blocks.omega[1] = theta / dt;
  solver->step();
  m.blocks.vx[1] = m.blocks.vy[1] = m.blocks.omega[1] = 0.0;
  solver->step();
  std::vector<std::size_t> index;
  const std::vector<laws::PairContact> pair = joint_contacts(m, index);
  ASSERT_GE(pair.size(), 2u);
  double length = 0;
  for (const auto& c : pair) length += c.length;
  EXPECT_NEAR(length, a, 1e-9 * a);
  const laws::PairSection p = laws::pair_section(pair, length);
  // To 1e-4: the contact points are not exactly symmetric about the centre, so the turn adds a
  // little to Fn. The shear spring is on the corners' arc centres, d inside block 0, which the
  // turn shears by theta d more; they sit where block 1's straight edge meets its end arcs,
  // whose shear coordinate differs from the edge's by the overlap over the radii (delta / 2d,
  // 5e-4): to 1e-3.
  EXPECT_NEAR(p.section.fn, jkn * length * delta, 1e-4 * jkn * length * delta);
  const double sheared = u + theta * m.rounding_length;
  EXPECT_NEAR(std::abs(p.section.fs), jks * length * sheared, 1e-3 * jks * length * sheared);
  EXPECT_NEAR(std::abs(p.section.m), jkn * p.inertia * theta, 1e-3 * jkn * p.inertia * theta);
  // The pair's points sit near the joint's ends: J is close to D^3 / 4 (three times the beam's),
  // and the section's stress at D is the larger of the two contacts' stresses.
  EXPECT_NEAR(p.inertia, a * a * a / 4.0, 0.05 * a * a * a / 4.0);
  double most = -1e300;
  for (const auto& c : pair) most = std::max(most, -c.fn / c.length);
  EXPECT_NEAR(laws::bond_tension(p.section), most, 1e-9 * std::abs(most));

  const double xi = 0.6;
  const std::vector<laws::PairContact> shrunk = laws::shrink_pair(pair, p, xi);
  for (std::size_t n = 0; n < index.size(); ++n) {
    laws::BondView b;
    ASSERT_TRUE(solver->bond(index[n], b));
    b.kn *= xi;
    b.ks *= xi;
    solver->set_bond(index[n], b, shrunk[n].fn, shrunk[n].fs);
  }
  solver->step();  // no motion: the law's own forces at the unchanged displacements
  const laws::PairSection q = laws::pair_section(joint_contacts(m, index), xi * length);
  EXPECT_NEAR(q.section.fn, xi * p.section.fn, 1e-9 * p.section.fn);
  EXPECT_NEAR(q.section.fs, xi * p.section.fs, 1e-9 * std::abs(p.section.fs));
  EXPECT_NEAR(q.section.m, xi * xi * xi * p.section.m, 1e-9 * std::abs(p.section.m));
  // The shrunk section's stress is the paper's eq. 17: -Fn / A + xi |M| R / I.
  laws::BondSection shrunk_section = q.section;
  shrunk_section.bending = p.section.bending;
  EXPECT_NEAR(
      laws::bond_tension(shrunk_section),
      -p.section.fn / length + xi * p.section.bending * std::abs(p.section.m) / (length * length),
      1e-6 * std::abs(p.section.fn / length));
}

// What assess_contacts skips a contact's integral by: exceeds(limit) holds exactly when the
// integral passes the limit by more than rounding, over stresses from activation to the edge of
// failure and factors from 1 down to near the floor.
TEST(StressCorrosion, HeldTimeExceedsALimitExactlyWhenItsIntegralPassesIt) {
  const laws::StrengthDegradation law{25.8, 0.4, 0.01};
  const laws::InitialStrength p0{10e6, 40e6, std::tan(40.0 * M_PI / 180.0)};
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  for (int k = 0; k < 2000; ++k) {
    const laws::ContactStress st{(unit(random) - 0.5) * 2.0 * p0.tension,
                                 unit(random) * 1.5 * p0.cohesion};
    const double lambda = 0.05 + 0.95 * unit(random);
    const double m = laws::stress_level(st, p0, lambda);
    if (m >= 1.0 || m < law.m_s) continue;
    const double floor = laws::min_strength_factor(law, st, p0);
    const auto rate = [&](double v) {
      return laws::factor_rate(law, 1e-10, laws::stress_level(st, p0, v));
    };
    const double t = laws::held_time(rate, lambda, floor);
    ASSERT_TRUE(std::isfinite(t) && t > 0) << "m " << m;
    EXPECT_TRUE(laws::held_time_exceeds(rate, lambda, floor, t * (1 - 1e-6)));
    EXPECT_FALSE(laws::held_time_exceeds(rate, lambda, floor, t));
    EXPECT_FALSE(laws::held_time_exceeds(rate, lambda, floor, t * (1 + 1e-6)));
    ++compared;
  }
  EXPECT_GT(compared, 200);
}

namespace {
namespace fs = std::filesystem;
namespace run = vorodec::testing;
const fs::path kSmall = fs::path(VORODEC_SOURCE_DIR) / "tests/models/corrosion_small.toml";

const fs::path& small_run() {
  static const fs::path out = [] {
    const fs::path o = run::out_dir("corrosion_small");
    EXPECT_EQ(
        run::run_vorodec("run " + kSmall.string() + " --threads 1 --no-vtk --out " + o.string()),
        0);
    return o;
  }();
  return out;
}

// The number after "key": in a JSON text (NaN if absent or null).
double json_value(const std::string& json, const std::string& key) {
  const auto pos = json.rfind("\"" + key + "\": ");
  if (pos == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + pos + key.size() + 4, nullptr);
}
}  // namespace

TEST(StressCorrosion, FatigueStageHoldsItsStressAndCreepsUntilTheSpecimenCollapses) {
  const std::string json = run::slurp(small_run() / "summary.json");
  EXPECT_NE(json.find("static-fatigue failure in stage 'fatigue'"), std::string::npos) << json;
  const double failure = json_value(json, "failure_time_s");
  EXPECT_GT(failure, 0.0);
  EXPECT_LT(failure, 10 * 86400.0);
  EXPECT_GT(json_value(json, "corrosion_steps"), 10.0);
  EXPECT_GT(json_value(json, "broken_transgranular") + json_value(json, "broken_intergranular"),
            0.0);
  // The equilibria: the held stress (rs 0.8 of 45 MPa above 0.01 MPa), a clock that only runs
  // forward, an axial strain that grows (creep) and cracks that accumulate.
  std::ifstream in(small_run() / "history.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_NE(header.find("corrosion_time"), std::string::npos);
  const auto column = [&](const std::string& name) {
    std::stringstream ss(header);
    std::size_t i = 0;
    for (std::string cell; std::getline(ss, cell, ','); ++i)
      if (cell == name) return i;
    ADD_FAILURE() << name;
    return i;
  };
  const std::size_t t = column("corrosion_time"), e = column("axial_strain"),
                    s = column("axial_stress"), n = column("cracks_tensile");
  const double target = 1e4 + 0.8 * (45e6 - 1e4);
  std::vector<std::vector<double>> eq;
  std::ifstream again(small_run() / "history.csv");
  std::getline(again, header);
  for (std::string line; std::getline(again, line);)
    if (line.find("fatigue:equilibrium") != std::string::npos) {
      std::vector<double> row;
      std::stringstream ss(line);
      for (std::string cell; std::getline(ss, cell, ',');) row.push_back(std::atof(cell.c_str()));
      eq.push_back(row);
    }
  ASSERT_GT(eq.size(), 10u);
  for (std::size_t k = 0; k < eq.size(); ++k) {
    EXPECT_NEAR(eq[k][s], target, 0.01 * target) << "equilibrium " << k;
    if (k == 0) continue;
    EXPECT_GE(eq[k][t], eq[k - 1][t]);
    EXPECT_GE(eq[k][n], eq[k - 1][n]);
  }
  EXPECT_GT(eq.back()[e], eq.front()[e]);
  EXPECT_NEAR(eq.back()[t], failure, 1e-6 * failure);
}

TEST(StressCorrosion, CracksOfAFatigueStageCarryTheCorrosionClock) {
  const auto cracks = run::read_csv(small_run() / "cracks.csv");
  const double failure = json_value(run::slurp(small_run() / "summary.json"), "failure_time_s");
  ASSERT_FALSE(cracks.empty());
  double last = 0;
  std::size_t later = 0;
  for (const auto& c : cracks) {
    EXPECT_GE(c[0], last) << "cracks in the order they formed";
    EXPECT_LE(c[0], failure * (1 + 1e-9));
    last = c[0];
    later += c[0] > 0;
  }
  EXPECT_GT(later, 0u) << "cracks formed under corrosion carry its time";
}

TEST(StressCorrosion, NothingCorrodesBelowTheActivationThresholds) {
  const fs::path out = run::out_dir("corrosion_inactive");
  ASSERT_EQ(
      run::run_vorodec("run " + kSmall.string() + " --threads 1 --no-vtk --out " + out.string() +
                       " --set corrosion.activation_stress=1e9"
                       " --set corrosion.activation_level=0.99"
                       " --set 'stage[0].driving_stress_ratio=0.3'"),
      0);
  const std::string json = run::slurp(out / "summary.json");
  EXPECT_NE(json.find("no bond corrodes"), std::string::npos) << json;
  EXPECT_EQ(json_value(json, "corrosion_time_s"), 0.0);
  EXPECT_EQ(json_value(json, "corrosion_steps"), 0.0);
}

// Corrosion degrades what a law offers as a degradable bond; Burger's contacts offer none (their
// strength sits behind Maxwell and Kelvin springs the layers have no reading of), so a corrosion
// stage on them is refused with that reason, not run on a law it cannot weaken.
TEST(StressCorrosion, CorrosionOfBurgersContactsIsRefusedWithItsReason) {
  const run::Outcome o = run::run_capture(
      "check " + kSmall.string() +
      " --set 'joints.transgranular={law=\"burgers\", kmn=4e13, kms=1.6e13, cmn=4e17, "
      "cms=1.6e17, kkn=8e13, kks=3.2e13, ckn=8e15, cks=3.2e15, tension=16e6, cohesion=32e6, "
      "friction=35}'");
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("law 'burgers' has none"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("transgranular"), std::string::npos) << o.output;
}
