#pragma once
// Helpers shared by the Voronoi builder and the specimen report (no CGAL here).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vorodec/geometry/point.hpp"
#include "vorodec/geometry/tessellation.hpp"

namespace vorodec::geometry::detail {

using Block = std::vector<std::uint32_t>;
using Blocks = std::vector<Block>;

// Undirected edge a < b and the number of blocks using it (2 = shared, 1 = outline).
struct Edge {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  std::uint32_t uses = 0;
};

struct CollapseSummary {
  std::size_t edges = 0;
  double min_edge_length = 0.0;   // m
  double max_shift = 0.0;         // m, largest vertex displacement caused by the collapse
  std::size_t relaxed_seeds = 0;  // seeds of too thin cells moved to their cell centroid first
};

// Unique edges sorted by (a, b).
std::vector<Edge> collect_edges(const Blocks& blocks);

double length(Point a, Point b);
double signed_area(const std::vector<Point>& vertices, const Block& block);
Point centroid(const std::vector<Point>& vertices, const Block& block);

SpecimenReport build_report(const std::vector<Point>& vertices, const Blocks& blocks,
                            double outline_area, const CollapseSummary& collapse);

}  // namespace vorodec::geometry::detail
