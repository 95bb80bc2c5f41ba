#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "cases.hpp"
#include "scenes.hpp"
#include "vorodec/geometry/tessellation.hpp"

namespace vorodec::verification {

UndampedEnergy undamped_energy(long steps, double safety, double shear_stiffness) {
  const auto t0 = std::chrono::steady_clock::now();
  geometry::TessellationSettings ts;
  ts.outline = {geometry::OutlineKind::rectangle, 0.01, 0.01, 0, 0};
  ts.block_count = 30;
  ts.seed = 3;
  ts.lloyd_iterations = 2;
  ts.min_edge_length = 2e-4;
  model::Model m = model::build_model(geometry::tessellate(ts), {2600.0, 2e-5, false});
  solver::SolverSettings s;
  s.local_damping = 0.0;
  s.safety_factor = safety;
  // Mohr-Coulomb with strengths no contact reaches: elastic bonds, and no force across an open
  // unbonded gap (linear_elastic would pull every contact within the tolerance shut).
  auto solver = make_solver(m, "mohr_coulomb",
                            params({{"jkn", 1.8e13},
                                    {"jks", shear_stiffness},
                                    {"tension", 1e12},
                                    {"cohesion", 1e12},
                                    {"friction", 25.5},
                                    {"dilation", 0},
                                    {"residual_friction", 25.5}}),
                            s);
  auto& bl = m.blocks;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t b = 0; b < bl.size(); ++b) {  // m/s and rad/s: ~1e-2 m/s at the corners
    bl.vx[b] = 0.01 * u(rng);
    bl.vy[b] = 0.01 * u(rng);
    bl.omega[b] = 10.0 * u(rng);
  }
  UndampedEnergy r;
  r.blocks = bl.size();
  r.contacts = m.contacts.size();
  std::vector<double> vx, vy, om;
  double e0_shadow = 0, e0_plain = 0, first = 0, last = 0;
  const long tenth = std::max(steps / 10, 1L);
  for (long n = 0; n < steps; ++n) {
    vx = bl.vx;
    vy = bl.vy;
    om = bl.omega;
    solver->step();
    // After step n the contact forces belong to x^n, the velocities before and after it to
    // n - 1/2 and n + 1/2: their product is the kinetic energy at n (exact invariant if linear).
    double shadow = 0;
    for (std::size_t b = 0; b < bl.size(); ++b)
      shadow += 0.5 * (bl.mass[b] * (vx[b] * bl.vx[b] + vy[b] * bl.vy[b]) +
                       bl.inertia[b] * om[b] * bl.omega[b]);
    const double strain = solver->contact_strain_energy();
    const double e_shadow = shadow + strain, e_plain = solver->kinetic_energy() + strain;
    if (n == 0) {
      e0_shadow = e_shadow;
      e0_plain = e_plain;
    }
    r.shadow = std::max(r.shadow, std::abs(e_shadow - e0_shadow) / e0_shadow);
    if (n < tenth) first += e_shadow;
    if (n >= steps - tenth) last += e_shadow;
    r.plain = std::max(r.plain, std::abs(e_plain - e0_plain) / e0_plain);
  }
  r.drift = std::abs(last - first) / static_cast<double>(tenth) / e0_shadow;
  r.steps = solver->steps();
  r.dt = solver->dt();
  r.contacts = m.contacts.size();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace vorodec::verification
