// Contact detection finds a corner that sits far outside some of the other block's edge lines
// but within the tolerance of its outline: pruning candidates by edge-line distance would lose it.
#include <gtest/gtest.h>

#include "scenes.hpp"

using namespace vorodec;
using model::Group;
using model::Point;

namespace {
constexpr double a = 0.01;  // m
}  // namespace

TEST(ContactDetection, FindsACornerInAConcaveNotchOfTheOtherBlock) {
  model::Model m;
  m.rounding_length = 0.01 * a;
  const double d = m.rounding_length;
  // A U-shaped block, its notch 1a wide with its floor at y = a.
  const std::vector<Point> u{{0, 0},         {3 * a, 0},     {3 * a, 3 * a}, {2 * a, 3 * a},
                             {2 * a, 1 * a}, {1 * a, 1 * a}, {1 * a, 3 * a}, {0, 3 * a}};
  // A diamond in the notch, its bottom vertex 0.2 d above the floor, half a notch away from the
  // walls: 0.5a outside two of the U's edge lines, within the tolerance d of the floor.
  const double y0 = a + 0.2 * d, s = 0.4 * a;
  const std::vector<Point> diamond{
      {1.5 * a, y0}, {1.5 * a + s, y0 + s}, {1.5 * a, y0 + 2 * s}, {1.5 * a - s, y0 + s}};
  model::add_block(m, u, 2600, Group::specimen);
  model::add_block(m, diamond, 2600, Group::specimen);
  solver::SolverSettings settings;
  auto solver = verification::make_solver(
      m, "linear_elastic", verification::params({{"jkn", 1e10}, {"jks", 1e10}}), settings);

  const std::uint32_t bottom = m.blocks.corner_begin[1];
  ASSERT_EQ(m.contacts.size(), 1u);
  const model::Contact& c = m.contacts[0];
  EXPECT_EQ(c.a, 1);
  EXPECT_EQ(c.b, 0);
  EXPECT_EQ(c.corner, bottom);
  EXPECT_EQ(c.edge, m.blocks.corner_begin[0] + 4);  // the floor, (2a, a) -> (a, a)
  EXPECT_GT(c.gap, 0.0);
  EXPECT_LE(c.gap, d);
}
