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

// A corner next to an edge shorter than 2 d has an arc that meets that edge's line beyond the
// edge, outside the block's corner box. A corner of another block within the tolerance of that
// arc, but farther from the box than the tolerance plus its own radius, still gets a contact.
TEST(ContactDetection, FindsACornerNearAnArcThatReachesPastItsBlocksBox) {
  model::Model m;
  const double d = 1e-4;  // m
  m.rounding_length = d;
  // Right side at x = 10 d, then an edge 0.11 d long up and to the left to W = (9.95 d, 5.1 d).
  // W's arc meets the line of that short edge at (10.4 d, 4.2 d), right of the box.
  const std::vector<Point> block{
      {0, 0}, {10 * d, 0}, {10 * d, 5 * d}, {9.95 * d, 5.1 * d}, {0, 10 * d}};
  // A diamond whose left corner points at that arc from 0.68 d away (its arc centre 2.2 d right
  // of the box: beyond the tolerance d plus its radius d).
  const double x = 10.783 * d, y = 4.206 * d, s = 3 * d;
  const std::vector<Point> diamond{{x + s, y - s}, {x + 2 * s, y}, {x + s, y + s}, {x, y}};
  model::add_block(m, block, 2600, Group::specimen);
  model::add_block(m, diamond, 2600, Group::specimen);
  solver::SolverSettings settings;
  auto solver = verification::make_solver(
      m, "linear_elastic", verification::params({{"jkn", 1e10}, {"jks", 1e10}}), settings);

  ASSERT_EQ(m.contacts.size(), 1u);
  const model::Contact& c = m.contacts[0];
  EXPECT_EQ(c.a, 1);
  EXPECT_EQ(c.b, 0);
  EXPECT_EQ(c.corner, m.blocks.corner_begin[1] + 3);  // the diamond's left corner
  EXPECT_EQ(c.edge, m.blocks.corner_begin[0] + 3);    // W -> (0, 10 d), whose start arc is W's
  EXPECT_GT(c.gap, 0.6 * d);
  EXPECT_LT(c.gap, 0.8 * d);
}

// A thin block with a straight "corner" on its far side (collinear edges, as edge collapsing in a
// Voronoi specimen leaves them) has an arc of the largest radius (4 d) whose centre lies below the
// block's near side: its circle pokes through the block into the neighbour below. The arc faces
// away from that neighbour, so the corner is no contact. It once was taken for one 5 d deep here
// (2 d in the granite whose block-bar impact at 15 m/s stopped on that "overlap").
TEST(ContactDetection, AStraightCornerOnTheFarSideOfAThinBlockIsNoContactWithTheBlockBelow) {
  model::Model m;
  const double d = 1e-4;  // m
  m.rounding_length = d;
  const std::vector<Point> below{{0, -10 * d}, {20 * d, -10 * d}, {20 * d, 0}, {0, 0}};
  const std::vector<Point> sliver{
      {2 * d, 0}, {18 * d, 0}, {18 * d, 3 * d}, {10 * d, 3 * d}, {2 * d, 3 * d}};
  model::add_block(m, below, 2600, Group::specimen);
  model::add_block(m, sliver, 2600, Group::specimen);
  const std::uint32_t apex = m.blocks.corner_begin[1] + 3;
  ASSERT_DOUBLE_EQ(m.blocks.shape[apex].radius, 4 * d);
  solver::SolverSettings settings;
  auto solver = verification::make_solver(
      m, "linear_elastic", verification::params({{"jkn", 1e10}, {"jks", 1e10}}), settings);

  ASSERT_FALSE(m.contacts.empty());
  for (const model::Contact& c : m.contacts) {
    EXPECT_NE(c.corner, apex);
    EXPECT_GT(c.gap, -1e-9 * d);  // the sliver only touches: nothing overlaps
  }
}
