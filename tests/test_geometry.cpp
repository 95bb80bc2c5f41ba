// Specimen geometry: Voronoi tessellation of rectangle and disc outlines (watertight shared vertex
// table, areas, reproducibility, edge collapse, block-count and mean-edge targets, Lloyd).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "vorodec/geometry/tessellation.hpp"

namespace {

using namespace vorodec::geometry;

using Block = std::vector<std::uint32_t>;

constexpr double kWidth = 0.05;
constexpr double kHeight = 0.1;
constexpr double kDiameter = 0.05;
constexpr int kDiscSegments = 96;
// Largest reflex turn accepted after the edge collapse ("nearly convex").
constexpr double kNearlyConvex = 0.5 * std::numbers::pi / 180;

TessellationSettings rectangle(int blocks, std::uint64_t seed = 1) {
  TessellationSettings s;
  s.outline = {OutlineKind::rectangle, kWidth, kHeight, 0.0, 0};
  s.block_count = blocks;
  s.seed = seed;
  return s;
}

TessellationSettings disc(int blocks, std::uint64_t seed = 1) {
  TessellationSettings s;
  s.outline = {OutlineKind::disc, 0.0, 0.0, kDiameter, kDiscSegments};
  s.block_count = blocks;
  s.seed = seed;
  return s;
}

double polygon_area(const std::vector<Point>& vertices, const Block& block) {
  double twice = 0;
  for (std::size_t i = 0; i < block.size(); ++i) {
    twice += cross(vertices[block[i]], vertices[block[(i + 1) % block.size()]]);
  }
  return twice / 2;
}

double total_area(const Tessellation& t) {
  double sum = 0;
  for (const Block& block : t.blocks) sum += polygon_area(t.vertices, block);
  return sum;
}

double distance(Point a, Point b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

using DirectedEdges = std::map<std::pair<std::uint32_t, std::uint32_t>, int>;

DirectedEdges directed_edges(const Tessellation& t) {
  DirectedEdges edges;
  for (const Block& block : t.blocks) {
    for (std::size_t i = 0; i < block.size(); ++i) {
      ++edges[{block[i], block[(i + 1) % block.size()]}];
    }
  }
  return edges;
}

std::vector<double> edge_lengths(const Tessellation& t) {
  std::vector<double> lengths;
  const DirectedEdges edges = directed_edges(t);
  for (const auto& [edge, count] : edges) {
    if (edge.first < edge.second || edges.count({edge.second, edge.first}) == 0) {
      lengths.push_back(distance(t.vertices[edge.first], t.vertices[edge.second]));
    }
  }
  return lengths;
}

double relative_spread(const std::vector<double>& values) {
  double mean = 0, square = 0;
  for (const double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  for (const double v : values) square += (v - mean) * (v - mean);
  return std::sqrt(square / static_cast<double>(values.size())) / mean;
}

// Outline segment of the disc polygon (corners at angles 2 pi k / n) closest in angle to p.
bool on_disc_segment(Point p, int segment, double tolerance) {
  const double r = kDiameter / 2;
  const auto corner = [&](int k) {
    const double angle = 2 * std::numbers::pi * k / kDiscSegments;
    return Point{r + r * std::cos(angle), r + r * std::sin(angle)};
  };
  const Point a = corner(segment), b = corner(segment + 1);
  return std::abs(cross(b - a, p - a)) / distance(a, b) <= tolerance;
}

bool on_rectangle_side(Point p, Point q, double tolerance) {
  const auto both = [&](auto on) { return on(p) && on(q); };
  return both([&](Point v) { return std::abs(v.x) <= tolerance; }) ||
         both([&](Point v) { return std::abs(v.x - kWidth) <= tolerance; }) ||
         both([&](Point v) { return std::abs(v.y) <= tolerance; }) ||
         both([&](Point v) { return std::abs(v.y - kHeight) <= tolerance; });
}

bool on_disc_outline(Point p, Point q, double tolerance) {
  const Point mid = 0.5 * (p + q) - Point{kDiameter / 2, kDiameter / 2};
  double angle = std::atan2(mid.y, mid.x);
  if (angle < 0) angle += 2 * std::numbers::pi;
  const int segment = static_cast<int>(angle / (2 * std::numbers::pi) * kDiscSegments);
  return on_disc_segment(p, segment, tolerance) && on_disc_segment(q, segment, tolerance);
}

// Every directed edge is matched by its reverse exactly once, or lies on the outline.
// Every edge is used once per direction; unmatched edges lie on the outline and the report's
// edge counts agree.
::testing::AssertionResult watertight(const Tessellation& t, bool is_disc) {
  const double tolerance = 1e-9 * kHeight;
  std::size_t boundary = 0;
  const DirectedEdges edges = directed_edges(t);
  for (const auto& [edge, count] : edges) {
    if (count != 1) return ::testing::AssertionFailure() << "edge used twice in the same direction";
    if (edges.count({edge.second, edge.first}) == 1) continue;
    ++boundary;
    const Point p = t.vertices[edge.first], q = t.vertices[edge.second];
    if (!(is_disc ? on_disc_outline(p, q, tolerance) : on_rectangle_side(p, q, tolerance)))
      return ::testing::AssertionFailure() << "unmatched edge not on the outline: (" << p.x << ","
                                           << p.y << ")-(" << q.x << "," << q.y << ")";
  }
  if (boundary != t.report.boundary_edges)
    return ::testing::AssertionFailure()
           << boundary << " boundary edges, report says " << t.report.boundary_edges;
  if ((edges.size() - boundary) / 2 != t.report.shared_edges)
    return ::testing::AssertionFailure() << (edges.size() - boundary) / 2
                                         << " shared edges, report says " << t.report.shared_edges;
  return ::testing::AssertionSuccess();
}

// Largest turn to the right (radians) along a block; <= 0 for a convex CCW polygon.
double worst_reflex_turn(const std::vector<Point>& vertices, const Block& block) {
  double worst = -std::numbers::pi;
  const std::size_t n = block.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point in = vertices[block[i]] - vertices[block[(i + n - 1) % n]];
    const Point out = vertices[block[(i + 1) % n]] - vertices[block[i]];
    worst = std::max(worst, -std::atan2(cross(in, out), dot(in, out)));
  }
  return worst;
}

TEST(Tessellation, BlockAreasSumToRectangleArea) {
  const Tessellation t = tessellate(rectangle(1300));
  EXPECT_NEAR(total_area(t) / (kWidth * kHeight), 1.0, 1e-9);
  EXPECT_NEAR(t.report.outline_area / (kWidth * kHeight), 1.0, 1e-12);
  for (const Block& block : t.blocks) EXPECT_GT(polygon_area(t.vertices, block), 0.0);
}

TEST(Tessellation, BlockAreasSumToDiscPolygonArea) {
  const Tessellation t = tessellate(disc(800));
  const double polygon = kDiscSegments / 2.0 * std::pow(kDiameter / 2, 2) *
                         std::sin(2 * std::numbers::pi / kDiscSegments);
  EXPECT_NEAR(t.report.outline_area / polygon, 1.0, 1e-12);
  EXPECT_NEAR(total_area(t) / polygon, 1.0, 1e-9);
}

TEST(Tessellation, SameSeedGivesBitwiseIdenticalResult) {
  TessellationSettings s = rectangle(500, 42);
  s.lloyd_iterations = 2;
  s.min_edge_length = 0.5e-3;
  const Tessellation a = tessellate(s), b = tessellate(s);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    EXPECT_EQ(a.vertices[i].x, b.vertices[i].x);
    EXPECT_EQ(a.vertices[i].y, b.vertices[i].y);
  }
  EXPECT_EQ(a.blocks, b.blocks);
}

TEST(Tessellation, DifferentSeedGivesDifferentResult) {
  const Tessellation a = tessellate(rectangle(500, 1)), b = tessellate(rectangle(500, 2));
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  bool differs = a.vertices.size() != b.vertices.size();
  for (std::size_t i = 0; !differs && i < a.vertices.size(); ++i) {
    differs = a.vertices[i].x != b.vertices[i].x || a.vertices[i].y != b.vertices[i].y;
  }
  EXPECT_TRUE(differs);
}

TEST(Tessellation, InteriorEdgesSharedOppositelyAndBoundaryEdgesOnRectangle) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    EXPECT_TRUE(watertight(tessellate(rectangle(700, seed)), false)) << "seed " << seed;
  }
}

TEST(Tessellation, InteriorEdgesSharedOppositelyAndBoundaryEdgesOnDisc) {
  for (const std::uint64_t seed : {1, 2}) {
    EXPECT_TRUE(watertight(tessellate(disc(500, seed)), true)) << "seed " << seed;
  }
}

TEST(Tessellation, DiscCornersAreVertices) {
  const Tessellation t = tessellate(disc(300));
  const double r = kDiameter / 2;
  for (int k = 0; k < kDiscSegments; ++k) {
    const double angle = 2 * std::numbers::pi * k / kDiscSegments;
    const Point corner{r + r * std::cos(angle), r + r * std::sin(angle)};
    const bool found = std::any_of(t.vertices.begin(), t.vertices.end(),
                                   [&](Point v) { return distance(v, corner) < 1e-12; });
    EXPECT_TRUE(found) << "outline corner " << k << " missing";
  }
}

// A flattened Brazilian disc: straight flats subtending 2 alpha at the top and the bottom, their
// ends outline corners, nothing beyond them, and the blocks fill the outline.
TEST(Tessellation, FlattenedDiscHasItsTwoFlats) {
  TessellationSettings s = disc(400);
  const double alpha = 10.0 * std::numbers::pi / 180, r = kDiameter / 2;
  s.outline.flat_angle = 2 * alpha;
  const Tessellation t = tessellate(s);
  const double half = r * std::sin(alpha), rise = r * std::cos(alpha);
  for (const double y : {r + rise, r - rise}) {
    for (const double x : {r - half, r + half}) {
      EXPECT_TRUE(std::any_of(t.vertices.begin(), t.vertices.end(),
                              [&](Point v) {
                                return distance(v, {x, y}) < 1e-12;
                              }))
          << "flat end " << x << ", " << y;
    }
  }
  for (const Point v : t.vertices) EXPECT_LE(std::abs(v.y - r), rise * (1 + 1e-12));
  // The circle less its two segments, to the polygon's chordal error (96 segments: 7e-4).
  const double area = std::numbers::pi * r * r - r * r * (2 * alpha - std::sin(2 * alpha));
  EXPECT_NEAR(t.report.outline_area / area, 1.0, 1e-3);
  EXPECT_NEAR(total_area(t) / t.report.outline_area, 1.0, 1e-9);
}

TEST(Tessellation, BlocksAreCounterClockwiseAndConvex) {
  const Tessellation t = tessellate(rectangle(1000, 7));
  for (const Block& block : t.blocks) {
    ASSERT_GE(block.size(), 3U);
    EXPECT_GT(polygon_area(t.vertices, block), 0.0);
    EXPECT_LE(worst_reflex_turn(t.vertices, block), 1e-9);
    EXPECT_EQ(std::set<std::uint32_t>(block.begin(), block.end()).size(), block.size());
  }
}

TEST(Tessellation, ShortEdgesAreCollapsedAndTopologyStaysWatertight) {
  TessellationSettings s = rectangle(1300, 5);
  s.min_edge_length = 0.4e-3;
  const Tessellation t = tessellate(s);
  EXPECT_GT(t.report.edges_collapsed, 0U);
  EXPECT_GE(t.report.edge_min, s.min_edge_length);
  for (const double len : edge_lengths(t)) EXPECT_GE(len, s.min_edge_length);
  const bool warned = std::any_of(t.report.warnings.begin(), t.report.warnings.end(),
                                  [](const std::string& w) { return w.find("collapsed") == 0; });
  EXPECT_TRUE(warned);
  EXPECT_TRUE(watertight(t, false));
  EXPECT_NEAR(total_area(t) / (kWidth * kHeight), 1.0, 1e-9);
  for (const Block& block : t.blocks) {
    EXPECT_GE(block.size(), 3U);
    EXPECT_LE(worst_reflex_turn(t.vertices, block), kNearlyConvex);
  }
}

TEST(Tessellation, ShortEdgesOnDiscAreCollapsedOntoTheOutline) {
  TessellationSettings s = disc(600, 3);
  s.outline.disc_segments = 0;
  s.min_edge_length = 0.3e-3;
  const Tessellation t = tessellate(s);
  EXPECT_GT(t.report.edges_collapsed, 0U);
  EXPECT_GE(t.report.edge_min, s.min_edge_length);
  EXPECT_NEAR(total_area(t) / t.report.outline_area, 1.0, 1e-9);
  for (const Block& block : t.blocks) {
    EXPECT_LE(worst_reflex_turn(t.vertices, block), kNearlyConvex);
  }
}

TEST(Tessellation, CollapseKeepsEveryBlockForModerateMinEdgeLength) {
  for (const std::uint64_t seed : {1, 2, 3, 4, 5, 6}) {
    TessellationSettings s = rectangle(1300, seed);
    s.min_edge_length = 0.3e-3;  // about a fifth of the mean edge
    const Tessellation t = tessellate(s);
    EXPECT_EQ(t.blocks.size(), 1300U);
    EXPECT_GE(t.report.edge_min, s.min_edge_length);
  }
}

TEST(Tessellation, MinEdgeLengthTooLargeForBlocksThrows) {
  TessellationSettings s = rectangle(1300);
  s.min_edge_length = 3e-3;
  EXPECT_THROW(tessellate(s), GeometryError);
}

TEST(Tessellation, BlockCountIsHonouredExactly) {
  for (const int n : {2, 3, 17, 1302}) {
    EXPECT_EQ(tessellate(rectangle(n)).blocks.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(tessellate(disc(n)).report.blocks, static_cast<std::size_t>(n));
  }
}

TEST(Tessellation, MeanEdgeLengthTargetIsReachedWithinFivePercent) {
  for (const int lloyd : {0, 3}) {
    TessellationSettings s = rectangle(0);
    s.mean_edge_length = 2e-3;
    s.lloyd_iterations = lloyd;
    EXPECT_NEAR(tessellate(s).report.edge_mean / s.mean_edge_length, 1.0, 0.05);
  }
  TessellationSettings s = disc(0);
  s.outline.disc_segments = 0;
  s.mean_edge_length = 1.5e-3;
  EXPECT_NEAR(tessellate(s).report.edge_mean / s.mean_edge_length, 1.0, 0.05);
}

TEST(Tessellation, LloydRelaxationRaisesSmallestAngleAndEvensEdgeLengths) {
  const Tessellation raw = tessellate(rectangle(1000, 9));
  TessellationSettings s = rectangle(1000, 9);
  s.lloyd_iterations = 3;
  const Tessellation relaxed = tessellate(s);
  EXPECT_GT(relaxed.report.smallest_angle_deg, raw.report.smallest_angle_deg);
  EXPECT_LT(relaxed.report.smallest_angle_deg, 180.0);
  EXPECT_LT(relaxed.report.edge_min, relaxed.report.edge_mean);
  EXPECT_LT(relative_spread(edge_lengths(relaxed)), 0.8 * relative_spread(edge_lengths(raw)));
}

TEST(Tessellation, BlocksAreNumberedAlongAHilbertCurve) {
  const Tessellation t = tessellate(rectangle(1300, 4));
  const auto centre = [&](const Block& block) {
    Point sum;
    for (const std::uint32_t v : block) sum = sum + t.vertices[v];
    return (1.0 / static_cast<double>(block.size())) * sum;
  };
  double step = 0;
  for (std::size_t b = 1; b < t.blocks.size(); ++b) {
    step += distance(centre(t.blocks[b - 1]), centre(t.blocks[b]));
  }
  step /= static_cast<double>(t.blocks.size() - 1);
  EXPECT_LT(step, 2.0 * std::sqrt(t.report.area_mean));
  EXPECT_EQ(t.blocks.front().front(), 0U) << "vertices are numbered in order of first use";
}

TEST(Tessellation, ReportIsConsistentWithTheBlocks) {
  const Tessellation t = tessellate(rectangle(600, 11));
  const SpecimenReport& r = t.report;
  std::size_t corners = 0;
  for (const Block& block : t.blocks) corners += block.size();
  EXPECT_EQ(r.blocks, t.blocks.size());
  EXPECT_EQ(2 * r.shared_edges + r.boundary_edges, corners);
  EXPECT_NEAR(r.area_mean * static_cast<double>(r.blocks), r.outline_area, 1e-12);
  EXPECT_LE(r.area_min, r.area_mean);
  EXPECT_LE(r.area_mean, r.area_max);
  EXPECT_LE(r.edge_min, r.edge_mean);
  EXPECT_LE(r.edge_mean, r.edge_max);
  EXPECT_GT(r.smallest_angle_deg, 0.0);
  EXPECT_LT(r.smallest_angle_deg, 120.0);
  EXPECT_EQ(r.edges_collapsed, 0U);
}

TEST(Tessellation, FormattedReportStatesUnits) {
  TessellationSettings s = rectangle(300);
  s.min_edge_length = 0.5e-3;
  const Tessellation t = tessellate(s);
  const std::string text = format_report(t.report);
  EXPECT_NE(text.find("300"), std::string::npos);
  EXPECT_NE(text.find(" mm\n"), std::string::npos);
  EXPECT_NE(text.find("mm^2"), std::string::npos);
  EXPECT_NE(text.find("degrees"), std::string::npos);
  EXPECT_NE(text.find("collapsed"), std::string::npos);
}

TEST(Tessellation, BadSettingsThrowGeometryError) {
  const auto throws = [](auto change) {
    TessellationSettings s = rectangle(100);
    change(s);
    EXPECT_THROW(tessellate(s), GeometryError);
  };
  throws([](TessellationSettings& s) { s.outline.width = 0; });
  throws([](TessellationSettings& s) { s.outline.height = -1; });
  throws([](TessellationSettings& s) { s.outline.width = std::nan(""); });
  throws([](TessellationSettings& s) { s.outline = {OutlineKind::disc, 0, 0, 0, 0}; });
  throws([](TessellationSettings& s) { s.block_count = 1; });
  throws([](TessellationSettings& s) { s.block_count = 0; });
  throws([](TessellationSettings& s) { s.mean_edge_length = 1e-3; });
  throws([](TessellationSettings& s) {
    s.block_count = 0;
    s.mean_edge_length = 0.2;
  });
  throws([](TessellationSettings& s) {
    s.block_count = 0;
    s.mean_edge_length = std::nan("");
  });
  throws([](TessellationSettings& s) { s.min_edge_length = -1e-3; });
  throws([](TessellationSettings& s) { s.lloyd_iterations = -1; });
}

}  // namespace
