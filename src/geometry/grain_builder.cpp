// Grain-based specimens: grains (Voronoi cells of the outline, or given polygons) get minerals by
// area fraction, then are cut into sub-blocks: Voronoi cells inside each grain (neighbouring
// grains' sub-blocks then share every boundary vertex after T-junction splitting), or triangles of
// one constrained Delaunay mesh whose constraints are the grain boundaries ("Trigon").
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "tessellation_internal.hpp"
#include "vorodec/geometry/grains.hpp"

namespace vorodec::geometry {
namespace {

using detail::Polygon;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using MeshVertex = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using MeshFace = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using MeshTds = CGAL::Triangulation_data_structure_2<MeshVertex, MeshFace>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, MeshTds, CGAL::Exact_predicates_tag>;
using MeshCriteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;

constexpr double kWeldTolerance = 1e-9;   // relative to the specimen size, as the Voronoi builder
constexpr double kMinAngleBound = 0.125;  // CGAL's B = sin^2(smallest angle): about 20.7 deg
// Longest-edge bound over the equal-area circle diameter of the target triangle; corrected once
// from the mesh's mean area.
constexpr double kTrigonSizeFactor = 1.9;

void require(bool condition, const std::string& message) {
  if (!condition) throw GeometryError(message);
}

double circle_area(double diameter) {
  return std::numbers::pi / 4 * diameter * diameter;
}

double polygon_area(const Polygon& p) {
  double twice = 0;
  for (std::size_t i = 0; i < p.size(); ++i) twice += cross(p[i], p[(i + 1) % p.size()]);
  return twice / 2;
}

bool is_convex(const Polygon& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point in = p[(i + 1) % p.size()] - p[i];
    const Point out = p[(i + 2) % p.size()] - p[(i + 1) % p.size()];
    if (cross(in, out) < -1e-12 * dot(in, in)) return false;
  }
  return true;
}

bool contains(const Polygon& p, Point q) {  // crossing number, any simple polygon
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y > q.y) != (p[j].y > q.y) &&
        q.x < p[j].x + (q.y - p[j].y) / (p[i].y - p[j].y) * (p[i].x - p[j].x))
      in = !in;
  }
  return in;
}

// Voronoi grains over the outline: tessellate() with the grain count (its Lloyd iterations and
// min_edge_length apply to the grains).
TessellationSettings grain_level(const TessellationSettings& s, double grain_size) {
  const double area = s.outline.kind == OutlineKind::rectangle ? s.outline.width * s.outline.height
                                                               : circle_area(s.outline.diameter);
  const double count = std::round(area / circle_area(grain_size));
  require(count >= 2, "grain_size is too large: fewer than 2 grains");
  require(count <= 5e6, "grain_size is too small: more than 5 million grains");
  TessellationSettings grains = s;
  grains.block_count = static_cast<int>(count);
  grains.mean_edge_length = 0;
  return grains;
}

std::vector<Polygon> polygons(const Tessellation& t) {
  std::vector<Polygon> out;
  for (const auto& block : t.blocks) {
    Polygon p;
    for (const std::uint32_t v : block) p.push_back(t.vertices[v]);
    out.push_back(std::move(p));
  }
  return out;
}

// Voronoi sub-blocks of each (convex) grain, Lloyd-relaxed inside the grain.
void voronoi_sub_blocks(const std::vector<Polygon>& grains, const GrainSettings& g,
                        std::uint64_t seed, std::vector<Polygon>& cells,
                        std::vector<std::int32_t>& tags) {
  const double target = circle_area(g.sub_block_size);
  for (std::size_t k = 0; k < grains.size(); ++k) {
    require(is_convex(grains[k]), "grain " + std::to_string(k) +
                                      " is not convex: Voronoi sub-blocks need convex grains "
                                      "(use sub_blocks = \"trigon\")");
    const auto n =
        static_cast<std::size_t>(std::max(1.0, std::round(polygon_area(grains[k]) / target)));
    Polygon seeds = detail::random_points_in(grains[k], seed * 0x9E3779B97F4A7C15ULL + k, n);
    for (int sweep = 0; sweep < g.sub_block_lloyd_iterations && n > 1; ++sweep) {
      const std::vector<Polygon> inner = detail::clipped_voronoi(seeds, grains[k]);
      std::transform(inner.begin(), inner.end(), seeds.begin(), detail::area_centroid);
    }
    for (Polygon& cell : detail::clipped_voronoi(seeds, grains[k])) {
      cells.push_back(std::move(cell));
      tags.push_back(static_cast<std::int32_t>(k));
    }
  }
}

// Grain of a point: the first grain whose box and polygon hold it (-1: none).
class GrainLocator {
 public:
  explicit GrainLocator(const std::vector<Polygon>& grains) : grains_(grains) {
    for (const Polygon& p : grains) {
      Point lo = p.front(), hi = p.front();
      for (const Point q : p) {
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
      }
      boxes_.push_back({lo, hi});
    }
  }
  std::int32_t find(Point q) const {
    for (std::size_t k = 0; k < grains_.size(); ++k) {
      const auto& [lo, hi] = boxes_[k];
      if (q.x < lo.x || q.x > hi.x || q.y < lo.y || q.y > hi.y) continue;
      if (contains(grains_[k], q)) return static_cast<std::int32_t>(k);
    }
    return -1;
  }

 private:
  const std::vector<Polygon>& grains_;
  std::vector<std::pair<Point, Point>> boxes_;
};

// Triangles of a constrained Delaunay mesh of the grains (longest edge <= size), by grain.
void mesh_triangles(const std::vector<Point>& vertices, const detail::Blocks& grain_blocks,
                    const GrainLocator& locator, double size, std::vector<Polygon>& cells,
                    std::vector<std::int32_t>& tags) {
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handle;
  handle.reserve(vertices.size());
  for (const Point p : vertices) handle.push_back(cdt.insert(Cdt::Point(p.x, p.y)));
  for (const detail::Block& b : grain_blocks)
    for (std::size_t i = 0; i < b.size(); ++i)
      cdt.insert_constraint(handle[b[i]], handle[b[(i + 1) % b.size()]]);
  CGAL::refine_Delaunay_mesh_2(cdt, MeshCriteria(kMinAngleBound, size));
  cells.clear();
  tags.clear();
  for (const auto f : cdt.finite_face_handles()) {
    if (!f->is_in_domain()) continue;
    Polygon t;
    for (int i = 0; i < 3; ++i) t.push_back({f->vertex(i)->point().x(), f->vertex(i)->point().y()});
    const std::int32_t grain = locator.find((1.0 / 3) * (t[0] + t[1] + t[2]));
    if (grain < 0) continue;  // a hole between given grains
    cells.push_back(std::move(t));
    tags.push_back(grain);
  }
}

void trigon_sub_blocks(const std::vector<Polygon>& grains, const GrainSettings& g, double tolerance,
                       std::vector<Polygon>& cells, std::vector<std::int32_t>& tags) {
  std::vector<Point> vertices;
  detail::Blocks grain_blocks;
  detail::weld_polygons(grains, tolerance, vertices, grain_blocks);
  const GrainLocator locator(grains);
  const double target = circle_area(g.sub_block_size);
  double size = kTrigonSizeFactor * g.sub_block_size;
  mesh_triangles(vertices, grain_blocks, locator, size, cells, tags);
  double area = 0;
  for (const Polygon& t : cells) area += polygon_area(t);
  size *= std::sqrt(target / (area / static_cast<double>(cells.size())));
  mesh_triangles(vertices, grain_blocks, locator, size, cells, tags);
}

Polygon counter_clockwise(Polygon p) {
  if (polygon_area(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}

}  // namespace

std::vector<std::int32_t> assign_minerals(std::span<const double> grain_areas,
                                          std::span<const double> fractions, std::uint64_t seed) {
  std::vector<std::size_t> order(grain_areas.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937_64 engine(seed);
  // Fisher-Yates by hand: std::shuffle's use of the engine is not specified across libraries.
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[engine() % i]);
  const double total = std::accumulate(grain_areas.begin(), grain_areas.end(), 0.0);
  std::vector<double> deficit(fractions.size());
  for (std::size_t m = 0; m < fractions.size(); ++m) deficit[m] = fractions[m] * total;
  std::vector<std::int32_t> mineral(grain_areas.size(), 0);
  for (const std::size_t k : order) {
    const auto m = static_cast<std::size_t>(std::max_element(deficit.begin(), deficit.end()) -
                                            deficit.begin());
    mineral[k] = static_cast<std::int32_t>(m);
    deficit[m] -= grain_areas[k];
  }
  return mineral;
}

Tessellation tessellate_grains(const TessellationSettings& settings, const GrainSettings& g) {
  require(g.sub_block_size > 0 && std::isfinite(g.sub_block_size),
          "sub_block_size must be positive");
  TessellationSettings s = settings;
  std::vector<Polygon> grains;
  std::vector<std::int32_t> grain_mineral;
  if (!g.grains.empty()) {
    Point lo = g.grains.front().corners.front(), hi = lo;
    for (const Grain& grain : g.grains)
      for (const Point p : grain.corners) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      }
    s.outline = {OutlineKind::rectangle, hi.x - lo.x, hi.y - lo.y, 0.0, 0};
    for (const Grain& grain : g.grains) {
      Polygon p;
      for (const Point q : grain.corners) p.push_back(q - lo);  // bounding box at the origin
      grains.push_back(counter_clockwise(std::move(p)));
      grain_mineral.push_back(grain.mineral);
    }
  } else {
    require(g.grain_size > 0 && std::isfinite(g.grain_size), "grain_size must be positive");
    s = grain_level(s, g.grain_size);
    grains = polygons(tessellate(s));
    std::vector<double> areas;
    for (const Polygon& p : grains) areas.push_back(polygon_area(p));
    grain_mineral = assign_minerals(areas, g.fractions, s.seed);
  }
  std::vector<Polygon> cells;
  std::vector<std::int32_t> tags;
  const double extent = std::max(s.outline.width, std::max(s.outline.height, s.outline.diameter));
  if (g.sub_blocks == SubBlocks::voronoi)
    voronoi_sub_blocks(grains, g, s.seed, cells, tags);
  else
    trigon_sub_blocks(grains, g, kWeldTolerance * extent, cells, tags);
  require(cells.size() >= 2, "fewer than 2 sub-blocks");
  Tessellation t = detail::assemble(cells, std::move(tags), s, detail::outline_segment_length(s));
  t.grain_mineral = std::move(grain_mineral);
  const auto minerals = static_cast<std::size_t>(
      std::max(static_cast<std::int32_t>(g.fractions.size()),
               *std::max_element(t.grain_mineral.begin(), t.grain_mineral.end()) + 1));
  t.mineral_area.assign(minerals, 0.0);
  for (std::size_t b = 0; b < t.blocks.size(); ++b)
    t.mineral_area[static_cast<std::size_t>(
        t.grain_mineral[static_cast<std::size_t>(t.block_grain[b])])] +=
        detail::signed_area(t.vertices, t.blocks[b]);
  return t;
}

}  // namespace vorodec::geometry
