// Rigid blocks through the real solver: Newton's third law, and the world refresh's rotations.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scenes.hpp"

using namespace vorodec;
using model::Group;

namespace {
constexpr double rho = 2600, a = 0.01;  // kg/m^3, m

model::Model two_squares_side_by_side() {
  model::Model m;
  m.rounding_length = 0.01 * a;
  model::add_block(m, verification::square(0, 0, a), rho, Group::specimen);
  model::add_block(m, verification::square(a, 0, a), rho, Group::specimen);
  return m;
}
}  // namespace

TEST(RigidBlocks, ContactForcesSumToZeroOverAllBlocks) {
  model::Model m = two_squares_side_by_side();
  model::add_block(m, verification::square(0, a, a), rho, Group::specimen);
  model::add_block(m, verification::square(a, a, a), rho, Group::specimen);
  solver::SolverSettings s;
  auto solver = verification::make_solver(m, "linear_elastic",
                                          verification::params({{"jkn", 1e10}, {"jks", 5e9}}), s);
  m.blocks.vx[0] = 0.01;
  m.blocks.omega[3] = 2.0;
  m.blocks.vy[2] = -0.02;
  double scale = 0;
  for (int i = 0; i < 200; ++i) solver->step();
  double fx = 0, fy = 0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    fx += solver->contact_force(b).x;
    fy += solver->contact_force(b).y;
  }
  for (const auto& c : m.contacts) scale += std::abs(c.fn) + std::abs(c.fs);
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(std::abs(fx) + std::abs(fy), 1e-12 * scale);
}

// A platen's velocity is the load path's: contact forces must not change it, whatever mass it was
// given (its mass never enters the integration).
TEST(RigidBlocks, PrescribedBlockKeepsItsVelocityWhateverItsMass) {
  model::Model m;
  m.rounding_length = 0.01 * a;
  model::add_block(m, verification::square(0, 0, a), rho, Group::specimen);
  model::add_block(m, verification::square(a, 0, a), rho, Group::top_platen);
  m.blocks.mass[1] = 0.0;
  m.blocks.inertia[1] = 0.0;
  solver::SolverSettings s;
  auto solver = verification::make_solver(m, "linear_elastic",
                                          verification::params({{"jkn", 1e10}, {"jks", 5e9}}), s);
  m.blocks.vx[1] = -0.01;
  const double x0 = m.blocks.x[1];
  for (int i = 0; i < 100; ++i) solver->step();
  EXPECT_GT(std::abs(solver->contact_force(1).x), 0.0);  // the blocks do press on each other
  EXPECT_EQ(m.blocks.vx[1], -0.01);
  EXPECT_EQ(m.blocks.vy[1], 0.0);
  EXPECT_EQ(m.blocks.omega[1], 0.0);
  EXPECT_NEAR(m.blocks.x[1], x0 - 0.01 * solver->time(), 1e-12 * a);
}

// The world refresh computes small rotations by series, not libm: it must agree with std::cos and
// std::sin to one unit in the last place (10^7 random angles: at most 1) on both sides of its
// switch-over (0.25 rad), and a rotated corner must sit where the rotation puts it.
TEST(RigidBlocks, WorldRefreshRotationAgreesWithLibmToOneUlp) {
  const double angles[] = {0.0,  1e-9,  -3e-5,  0.01, -0.1, 0.2, 0.2499,
                           0.25, -0.25, 0.2501, 0.7,  -2.0, 3.1, 1e3};
  model::Model m;
  m.rounding_length = 0.01 * a;
  for (std::size_t i = 0; i < std::size(angles); ++i)
    model::add_block(m, verification::square(2.0 * a * double(i), 0, a), rho, Group::specimen);
  for (std::size_t i = 0; i < std::size(angles); ++i) m.blocks.theta[i] = angles[i];
  m.blocks.refresh_world();
  const double eps = std::numeric_limits<double>::epsilon();  // >= 1 ulp of a value times it
  for (std::size_t i = 0; i < std::size(angles); ++i) {
    const double c = std::cos(angles[i]), s = std::sin(angles[i]);
    EXPECT_NEAR(m.blocks.cos_t[i], c, eps * std::abs(c)) << "theta " << angles[i];
    EXPECT_NEAR(m.blocks.sin_t[i], s, eps * std::abs(s)) << "theta " << angles[i];
    const std::uint32_t k = m.blocks.corner_begin[i];
    const model::Point p = m.blocks.corner[k];
    EXPECT_NEAR(m.blocks.world[k].corner.x, m.blocks.x[i] + c * p.x - s * p.y, 1e-15);
    EXPECT_NEAR(m.blocks.world[k].corner.y, m.blocks.y[i] + s * p.x + c * p.y, 1e-15);
  }
}

// The damping's work is booked at each step's mean velocity, which is what the kinetic energy at
// half steps loses to it (the balance closes to 3e-6 here); booked at the new velocity, this
// heavily damped block on a spring at a coarse time step missed 18 % of its energy (measured).
TEST(RigidBlocks, DampedOscillationKeepsItsEnergyBalance) {
  model::Model m;
  m.rounding_length = 0.01 * a;
  model::add_block(m, verification::square(0, a, a), rho, Group::specimen);
  model::add_block(m, verification::square(0, 0, a), rho, Group::bottom_platen);
  solver::SolverSettings s;
  s.local_damping = 0.8;
  s.safety_factor = 0.5;
  auto solver = verification::make_solver(m, "linear_elastic",
                                          verification::params({{"jkn", 1e10}, {"jks", 1e10}}), s);
  m.blocks.vy[0] = 0.01;
  m.blocks.vx[0] = 0.004;
  const double e0 = solver->kinetic_energy();
  for (int i = 0; i < 400; ++i) solver->step();
  const double kept = solver->kinetic_energy() + solver->contact_strain_energy();
  ASSERT_LT(kept, 0.5 * e0);
  EXPECT_NEAR(kept + solver->energy().damping, e0, 1e-5 * e0);
}
