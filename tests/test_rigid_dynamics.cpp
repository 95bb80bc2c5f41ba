// Newton's third law through the real solver (the analytic scenes are verification cases).
#include <gtest/gtest.h>

#include <cmath>

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
