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

using Polygon = std::vector<Point>;

// The length of the straight segments tessellate(settings) cuts a disc outline into.
double outline_segment_length(const TessellationSettings& settings);

// `count` uniform random points inside a convex counter-clockwise polygon (reproducible).
Polygon random_points_in(const Polygon& region, std::uint64_t seed, std::size_t count);

// Voronoi cells of the seeds clipped to a convex counter-clockwise polygon holding them.
std::vector<Polygon> clipped_voronoi(const Polygon& seeds, const Polygon& region);

Point area_centroid(const Polygon& polygon);

// Joins polygon corners closer than the tolerance into one shared vertex table.
void weld_polygons(const std::vector<Polygon>& polygons, double tolerance,
                   std::vector<Point>& vertices, Blocks& blocks);

// Inserts into every block edge the vertices that lie on it (T-junctions, e.g. where sub-blocks
// of two grains meet along a grain boundary), so that neighbours share every boundary vertex.
void split_t_junctions(const std::vector<Point>& vertices, Blocks& blocks, double tolerance);

// Cells tiling settings.outline (as outline_corners with segment_length) into a tessellation:
// welded into a shared vertex table, T-junctions split, edges shorter than
// settings.min_edge_length collapsed, blocks numbered along the Hilbert curve (tags follow).
Tessellation assemble(const std::vector<Polygon>& cells, std::vector<std::int32_t> tags,
                      const TessellationSettings& settings, double segment_length);

SpecimenReport build_report(const std::vector<Point>& vertices, const Blocks& blocks,
                            double outline_area, const CollapseSummary& collapse);

}  // namespace vorodec::geometry::detail
