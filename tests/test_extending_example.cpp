// The worked example of docs/extending.md, "Adding a contact law": a brittle linear spring that
// breaks in tension, run by the real solver through LawGroupOf. Its checks are what a new law's
// first verification case checks: the joint breaks at its strength, as tensile cracks.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "scenes.hpp"
#include "vorodec/laws/law_group.hpp"

using namespace vorodec;

namespace {

// Step 1: the law. Parameters from the model file, properties sampled per contact, state per
// contact, and evaluate() for one contact per step (docs/extending.md explains each member).
struct BrittleSpring {
  static constexpr std::string_view name = "brittle_spring";
  struct Params {
    model::Distribution jkn, jks, tension;  // Pa/m, Pa/m, Pa
  };
  struct Props {
    double kn, ks, tension_force;  // N/m, N/m, N (per m thickness)
  };
  static constexpr std::array<std::string_view, 3> property_names{"kn [N/m]", "ks [N/m]",
                                                                  "tension [N]"};
  struct State {
    double fs = 0;      // N
    double origin = 0;  // m, gap at which the normal spring is unloaded
    bool broken = false;
  };

  static Params params_from(const laws::LawParams& p) {
    return {p.at("jkn"), p.at("jks"), p.at("tension")};
  }
  // Each property draws from its own stream (0, 1, 2) keyed by the contact's id: reproducible.
  static Props sample(const Params& p, std::uint64_t seed, const laws::NewContact& c) {
    return {p.jkn.sample(seed, c.id, 0) * c.length, p.jks.sample(seed, c.id, 1) * c.length,
            p.tension.sample(seed, c.id, 2) * c.length};
  }
  static State initial_state(const laws::NewContact& c) {
    return {0.0, c.spring_origin, !c.bonded};
  }
  static double max_stiffness(const Props& p) { return std::max(p.kn, p.ks); }
  static double strain_energy(const Props& p, double fn, double fs) {
    return 0.5 * (fn * fn / p.kn + fs * fs / p.ks);
  }
  static laws::LawResult evaluate(const laws::ContactKinematics& k, const Props& p, State& st) {
    const double fn = -p.kn * (k.gap - st.origin);
    st.fs -= p.ks * k.du_s;
    if (!st.broken && -fn > p.tension_force) {
      st.broken = true;
      return {0.0, 0.0, laws::ContactEvent::tensile_failure, false};
    }
    if (st.broken) return {std::max(fn, 0.0), 0.0, laws::ContactEvent::none, fn >= 0};
    return {fn, st.fs, laws::ContactEvent::none, true};
  }
};

}  // namespace

// Step 2: run it. Two 10 mm squares glued by the law, pulled apart at a slow constant speed.
TEST(ExtendingExample, BrittleSpringBreaksInTensionAtItsStrength) {
  const double a = 0.01, tension = 5e6;  // m, Pa
  model::Model m;
  m.rounding_length = 0.01 * a;
  model::add_block(m, verification::square(0, 0, a), 2600, model::Group::specimen);
  model::add_block(m, verification::square(a, 0, a), 2600, model::Group::specimen);
  std::vector<std::unique_ptr<laws::LawGroup>> groups;
  groups.push_back(std::make_unique<laws::LawGroupOf<BrittleSpring>>(
      verification::params({{"jkn", 1e12}, {"jks", 1e12}, {"tension", tension}}), 7));
  solver::LawTable table;
  for (auto& row : table.law) row.fill(0);
  solver::SolverSettings s;
  s.local_damping = 0.0;
  s.contact_tolerance = m.rounding_length;
  solver::Solver solver(m, std::move(groups), table, s);
  solver.initialise();
  // Both blocks driven (their velocities prescribed, not integrated), 1 mm/s apart.
  m.blocks.prescribed[0] = m.blocks.prescribed[1] = 1;
  m.blocks.vx[0] = -0.5e-3;  // m/s
  m.blocks.vx[1] = 0.5e-3;
  double pulled = 0;  // N per m thickness, the largest total tension before the break
  for (int i = 0; i < 20000 && solver.cracks().empty(); ++i) {
    solver.step();
    double total = 0;
    for (const model::Contact& c : m.contacts) total -= c.fn;
    pulled = std::max(pulled, total);
  }
  // The joint's two point contacts, pulled evenly, fail in the same step, each as a tensile crack.
  ASSERT_EQ(solver.cracks().size(), 2u);
  for (const laws::CrackEvent& e : solver.cracks())
    EXPECT_EQ(e.type, laws::ContactEvent::tensile_failure);
  EXPECT_NEAR(pulled, tension * a, 0.02 * tension * a);
}
