// Voronoi tessellation of the specimen outline. Seeds -> Delaunay neighbours (CGAL) -> each cell
// is the outline clipped by the bisectors of its neighbours -> vertices welded into one table ->
// short edges collapsed -> blocks numbered along a Hilbert curve.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tessellation_internal.hpp"
#include "vorodec/geometry/tessellation.hpp"

namespace vorodec::geometry {
namespace {

using detail::Block;
using detail::Blocks;
using detail::CollapseSummary;
using detail::length;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using FaceBase = CGAL::Triangulation_face_base_2<Kernel>;
using Delaunay =
    CGAL::Delaunay_triangulation_2<Kernel,
                                   CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>>;

using Polygon = std::vector<Point>;

constexpr double kWeldTolerance = 1e-9;      // relative to the specimen size
constexpr double kPoissonEdgeFactor = 0.65;  // mean Voronoi edge ~ 0.65 sqrt(area / N)
constexpr double kCountTolerance = 0.003;    // relative mean-edge error that ends the count search
constexpr int kCountPasses = 5;
constexpr std::size_t kMaxBlocks = 50'000'000;  // keeps vertex indices within 32 bits
constexpr int kMaxCollapsePasses = 10'000;
constexpr int kThinCellSweeps = 10;
constexpr int kStraightenSweeps = 5;

void require(bool condition, const std::string& message) {
  if (!condition) throw GeometryError(message);
}

std::string mm(double metres) {
  std::ostringstream text;
  text.precision(4);
  text << metres * 1e3 << " mm";
  return text.str();
}

double smallest_extent(const Outline& o) {
  return o.kind == OutlineKind::rectangle ? std::min(o.width, o.height) : o.diameter;
}

void validate(const TessellationSettings& s) {
  const Outline& o = s.outline;
  for (const double v : {o.width, o.height, o.diameter, s.mean_edge_length, s.min_edge_length}) {
    require(std::isfinite(v), "geometry settings contain NaN or infinite values");
  }
  if (o.kind == OutlineKind::rectangle) {
    require(o.width > 0 && o.height > 0, "rectangle width and height must be positive");
  } else {
    require(o.diameter > 0, "disc diameter must be positive");
    require(o.disc_segments == 0 || o.disc_segments >= 3, "disc_segments must be 0 or >= 3");
  }
  require(s.mean_edge_length >= 0 && s.block_count >= 0 && s.min_edge_length >= 0 &&
              s.lloyd_iterations >= 0,
          "mean_edge_length, block_count, min_edge_length and lloyd_iterations must not be "
          "negative");
  require((s.mean_edge_length > 0) != (s.block_count > 0),
          "exactly one of mean_edge_length and block_count must be set");
  require(s.block_count == 0 || s.block_count >= 2, "at least 2 blocks are needed");
  require(static_cast<std::size_t>(s.block_count) <= kMaxBlocks, "block_count is too large");
  require(s.mean_edge_length < smallest_extent(o),
          "mean_edge_length (" + mm(s.mean_edge_length) + ") is larger than the specimen");
}

// Where a vertex sits on the outline: corner k lies on segments k-1 and k.
struct Location {
  int segment = -1;  // -1: interior
  int corner = -1;
};

// Convex, counter-clockwise outline polygon.
class OutlinePolygon {
 public:
  OutlinePolygon(const Outline& outline, double segment_length) {
    if (outline.kind == OutlineKind::rectangle) {
      hi_ = {outline.width, outline.height};
      corners_ = {lo_, {hi_.x, 0}, hi_, {0, hi_.y}};
    } else {
      uniform_ = true;
      make_disc(outline, segment_length);
    }
    centre_ = 0.5 * (lo_ + hi_);
  }

  const Polygon& corners() const { return corners_; }
  double extent() const { return std::max(hi_.x - lo_.x, hi_.y - lo_.y); }

  double area() const {
    double twice = 0;
    for (std::size_t k = 0; k < corners_.size(); ++k) twice += cross(corners_[k], corner(k + 1));
    return twice / 2;
  }

  bool contains(Point p) const {
    const std::size_t k = segment_towards(p);
    return cross(corner(k + 1) - corners_[k], p - corners_[k]) > 0;
  }

  // The cell (coordinates relative to `origin`) starts as the bounding box of the outline.
  Polygon bounding_box(Point origin) const {
    return {lo_ - origin, Point{hi_.x, lo_.y} - origin, hi_ - origin, Point{lo_.x, hi_.y} - origin};
  }

  // Cuts away the parts of a cell (relative to `origin`) outside a disc outline.
  template <typename Clip>
  void clip(Polygon& cell, Point origin, Clip&& clip_half_plane) const {
    if (is_box_ || inside_incircle(cell, origin)) return;
    for (std::size_t k = 0; k < corners_.size(); ++k) {
      const Point a = corners_[k] - origin;
      const Point d = corner(k + 1) - corners_[k];
      const Point outward{d.y, -d.x};
      clip_half_plane(cell, outward, dot(outward, a));
    }
  }

  Location locate(Point p, double tolerance) const {
    const std::size_t k = segment_towards(p);
    const std::size_t n = corners_.size();
    for (const std::size_t j : {k, (k + 1) % n, (k + n - 1) % n}) {
      if (length(p, corners_[j]) <= tolerance) {
        return {static_cast<int>(j), static_cast<int>(j)};
      }
    }
    for (const std::size_t j : {k, (k + 1) % n, (k + n - 1) % n}) {
      if (length(p, project(p, static_cast<int>(j))) <= tolerance) {
        return {static_cast<int>(j), -1};
      }
    }
    return {};
  }

  // Closest point of outline segment `segment`.
  Point project(Point p, int segment) const {
    const auto k = static_cast<std::size_t>(segment);
    const Point a = corners_[k];
    const Point d = corner(k + 1) - a;
    const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
    return a + t * d;
  }

  int corner_count() const { return static_cast<int>(corners_.size()); }

 private:
  void make_disc(const Outline& outline, double segment_length) {
    const double r = outline.diameter / 2;
    const int n = outline.disc_segments > 0
                      ? outline.disc_segments
                      : std::max(8, static_cast<int>(std::ceil(std::numbers::pi * outline.diameter /
                                                               segment_length)));
    const double step = 2 * std::numbers::pi / n, half_flat = outline.flat_angle / 2;
    // A flattened disc: straight flats for the platens, centred on the top and bottom and each
    // subtending flat_angle at the centre, between the polygon's points on the circle.
    std::vector<double> angles;
    if (half_flat > 0) {
      const double top = std::numbers::pi / 2, bottom = 3 * std::numbers::pi / 2;
      for (const double a :
           {top - half_flat, top + half_flat, bottom - half_flat, bottom + half_flat})
        angles.push_back(a);
      for (int k = 0; k < n; ++k) {
        const double a = step * k;
        // Off the flats, and not within half a segment of their ends (no sliver edges).
        if (std::abs(a - top) < half_flat + step / 2 || std::abs(a - bottom) < half_flat + step / 2)
          continue;
        angles.push_back(a);
      }
      std::sort(angles.begin(), angles.end());
      uniform_ = false;
    } else {
      for (int k = 0; k < n; ++k) angles.push_back(step * k);
    }
    for (const double a : angles) corners_.push_back({r + r * std::cos(a), r + r * std::sin(a)});
    lo_ = {0, r - r * std::cos(half_flat)};
    hi_ = {outline.diameter, r + r * std::cos(half_flat)};
    is_box_ = false;
    inradius_ = r * std::min(std::cos(std::numbers::pi / n), std::cos(half_flat));
  }

  Point corner(std::size_t k) const { return corners_[k % corners_.size()]; }

  bool inside_incircle(const Polygon& cell, Point origin) const {
    const double limit = inradius_ * (1 - 1e-12);
    return std::all_of(cell.begin(), cell.end(),
                       [&](Point v) { return length(v + origin, centre_) < limit; });
  }

  // The segment whose wedge (seen from the centre) contains p.
  std::size_t segment_towards(Point p) const {
    const Point v = p - centre_;
    const std::size_t n = corners_.size();
    if (uniform_) {
      double angle = std::atan2(v.y, v.x);
      if (angle < 0) angle += 2 * std::numbers::pi;
      return static_cast<std::size_t>(angle / (2 * std::numbers::pi) * static_cast<double>(n)) % n;
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (cross(corners_[k] - centre_, v) >= 0 && cross(corner(k + 1) - centre_, v) < 0) return k;
    }
    return 0;
  }

  Polygon corners_;
  Point lo_{0, 0}, hi_{0, 0}, centre_;
  double inradius_ = 0;
  bool is_box_ = true;
  bool uniform_ = false;  // a round disc's equal segments: the segment follows from the angle
};

// Hilbert index of (x, y) on a 2^16 x 2^16 grid.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t n = 1U << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0;
    const std::uint32_t ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

// Permutation ordering the points along a Hilbert curve over their bounding box (ties by index).
std::vector<std::size_t> hilbert_order(const std::vector<Point>& points) {
  Point lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Point hi{-lo.x, -lo.y};
  for (const Point p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  // One scale for both axes keeps the curve's locality isotropic.
  const double scale = 65535.0 / std::max({hi.x - lo.x, hi.y - lo.y, 1e-300});
  const auto grid = [&](double t) {
    return static_cast<std::uint32_t>(std::clamp(std::round(t * scale), 0.0, 65535.0));
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    keyed[i] = {hilbert_index(grid(points[i].x - lo.x), grid(points[i].y - lo.y)), i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = keyed[i].second;
  return order;
}

// Platform-independent uniform numbers in (0, 1) (std::uniform_real_distribution is not).
class UnitRandom {
 public:
  explicit UnitRandom(std::uint64_t seed) : engine_(seed) {}
  double next() { return (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53; }

 private:
  std::mt19937_64 engine_;
};

// The first k seeds do not depend on the count, so counts can be searched smoothly.
Polygon random_seeds(const OutlinePolygon& outline, std::uint64_t seed, std::size_t count) {
  UnitRandom random(seed);
  const Polygon box = outline.bounding_box({0, 0});
  Polygon seeds;
  seeds.reserve(count);
  while (seeds.size() < count) {
    const Point p{box[0].x + random.next() * (box[2].x - box[0].x),
                  box[0].y + random.next() * (box[2].y - box[0].y)};
    if (outline.contains(p)) seeds.push_back(p);
  }
  // Same seed set in spatial order: every later pass walks memory locally.
  Polygon sorted;
  sorted.reserve(count);
  for (const std::size_t i : hilbert_order(seeds)) sorted.push_back(seeds[i]);
  return sorted;
}

// Keeps the part of a convex polygon where dot(normal, x) <= offset.
class HalfPlaneClipper {
 public:
  void operator()(Polygon& polygon, Point normal, double offset) {
    side_.clear();
    for (const Point v : polygon) side_.push_back(dot(normal, v) - offset);
    if (std::all_of(side_.begin(), side_.end(), [](double s) { return s <= 0; })) return;
    scratch_.clear();
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if (side_[i] <= 0) scratch_.push_back(polygon[i]);
      if ((side_[i] <= 0) != (side_[j] <= 0)) {
        const double t = side_[i] / (side_[i] - side_[j]);
        scratch_.push_back(polygon[i] + t * (polygon[j] - polygon[i]));
      }
    }
    std::swap(polygon, scratch_);
  }

 private:
  std::vector<double> side_;
  Polygon scratch_;
};

using Neighbours = std::vector<std::vector<std::uint32_t>>;

// Without a two-dimensional triangulation (collinear seeds) every other seed is a neighbour.
Neighbours all_pairs(std::size_t count) {
  Neighbours neighbours(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    for (std::uint32_t j = 0; j < count; ++j) {
      if (i != j) neighbours[i].push_back(j);
    }
  }
  return neighbours;
}

Neighbours delaunay_neighbours(const Polygon& seeds) {
  std::vector<std::pair<Kernel::Point_2, std::uint32_t>> points;
  points.reserve(seeds.size());
  for (std::uint32_t i = 0; i < seeds.size(); ++i) points.push_back({{seeds[i].x, seeds[i].y}, i});
  Delaunay dt;
  dt.insert(points.begin(), points.end());
  require(dt.number_of_vertices() == seeds.size(), "coincident Voronoi seeds");
  if (dt.dimension() < 2) return all_pairs(seeds.size());
  Neighbours neighbours(seeds.size());
  for (const auto v : dt.finite_vertex_handles()) {
    auto& list = neighbours[v->info()];
    auto circulator = dt.incident_vertices(v);
    const auto first = circulator;
    do {
      if (!dt.is_infinite(circulator)) list.push_back(circulator->info());
    } while (++circulator != first);
    // Clipping order fixed by index, so round-off does not depend on CGAL's internal order.
    std::sort(list.begin(), list.end());
  }
  return neighbours;
}

// Cell coordinates are computed relative to the seed to keep round-off small.
std::vector<Polygon> voronoi_cells(const Polygon& seeds, const OutlinePolygon& outline) {
  const Neighbours neighbours = delaunay_neighbours(seeds);
  HalfPlaneClipper clip;
  std::vector<Polygon> cells(seeds.size());
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const Point p = seeds[i];
    Polygon cell = outline.bounding_box(p);
    for (const std::uint32_t j : neighbours[i]) {
      const Point n = seeds[j] - p;
      clip(cell, n, dot(n, n) / 2);
    }
    outline.clip(cell, p, clip);
    for (Point& v : cell) v = v + p;
    cells[i] = std::move(cell);
  }
  return cells;
}

Point polygon_centroid(const Polygon& polygon) {
  const Point origin = polygon.front();
  double twice = 0;
  Point sum;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Point p = polygon[i] - origin;
    const Point q = polygon[i + 1] - origin;
    const double a = cross(p, q);
    twice += a;
    sum = sum + (a / 3) * (p + q);
  }
  return origin + (1 / twice) * sum;
}

Polygon lloyd_step(const Polygon& seeds, const OutlinePolygon& outline) {
  const std::vector<Polygon> cells = voronoi_cells(seeds, outline);
  Polygon moved(seeds.size());
  std::transform(cells.begin(), cells.end(), moved.begin(), polygon_centroid);
  return moved;
}

// Drops consecutive repeats (cyclically) left by welding or collapsing.
void remove_repeats(Block& block) {
  block.erase(std::unique(block.begin(), block.end()), block.end());
  while (block.size() > 1 && block.front() == block.back()) block.pop_back();
}

struct Candidate {
  std::vector<Point> vertices;
  Blocks blocks;
  CollapseSummary collapse;
};

// Union-find whose root is the smallest member: a cluster's first appearance.
class FirstAppearance {
 public:
  explicit FirstAppearance(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  std::uint32_t root(std::uint32_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t ra = root(a), rb = root(b);
    parent_[std::max(ra, rb)] = std::min(ra, rb);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// Joins cell corners closer than the tolerance: a sweep over the corners sorted by x.
void unite_close_corners(const std::vector<Point>& corners, double tolerance,
                         FirstAppearance& clusters) {
  std::vector<std::pair<double, std::uint32_t>> by_x(corners.size());
  for (std::uint32_t i = 0; i < corners.size(); ++i) by_x[i] = {corners[i].x, i};
  std::sort(by_x.begin(), by_x.end());
  for (std::size_t i = 0; i < by_x.size(); ++i) {
    for (std::size_t j = i + 1; j < by_x.size() && by_x[j].first - by_x[i].first <= tolerance;
         ++j) {
      const std::uint32_t a = by_x[i].second, b = by_x[j].second;
      if (length(corners[a], corners[b]) <= tolerance) clusters.unite(a, b);
    }
  }
}

// Shared vertex table: a vertex keeps the coordinates of its first appearance.
Candidate weld_cells(const std::vector<Polygon>& cells, double tolerance) {
  std::vector<Point> corners;
  for (const Polygon& cell : cells) corners.insert(corners.end(), cell.begin(), cell.end());
  FirstAppearance clusters(corners.size());
  unite_close_corners(corners, tolerance, clusters);
  constexpr auto unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> vertex_of(corners.size(), unused);
  Candidate result;
  result.blocks.reserve(cells.size());
  std::uint32_t corner = 0;
  for (const Polygon& cell : cells) {
    Block block;
    block.reserve(cell.size());
    for (std::size_t k = 0; k < cell.size(); ++k, ++corner) {
      const std::uint32_t r = clusters.root(corner);
      if (vertex_of[r] == unused) {
        vertex_of[r] = static_cast<std::uint32_t>(result.vertices.size());
        result.vertices.push_back(corners[r]);
      }
      block.push_back(vertex_of[r]);
    }
    remove_repeats(block);
    require(block.size() >= 3, "degenerate Voronoi cell (seeds too close together)");
    result.blocks.push_back(std::move(block));
  }
  return result;
}

struct Target {
  Point position;
  Location location;
};

// Merges vertices joined by edges shorter than min_edge_length, keeping the outline intact.
class EdgeCollapser {
 public:
  EdgeCollapser(Candidate& candidate, const OutlinePolygon& outline, double min_edge,
                double tolerance)
      : vertices_(candidate.vertices),
        blocks_(candidate.blocks),
        outline_(outline),
        min_edge_(min_edge),
        original_(candidate.vertices),
        merged_into_(candidate.vertices.size()) {
    std::iota(merged_into_.begin(), merged_into_.end(), 0U);
    locations_.reserve(vertices_.size());
    for (const Point v : vertices_) locations_.push_back(outline_.locate(v, tolerance));
  }

  CollapseSummary run() {
    CollapseSummary summary{0, min_edge_, 0};
    for (int pass = 0; pass < kMaxCollapsePasses; ++pass) {
      const std::size_t collapsed = collapse_pass();
      if (collapsed == 0) break;
      summary.edges += collapsed;
    }
    if (summary.edges > 0) straighten_reflex_vertices();
    summary.max_shift = max_shift();
    return summary;
  }

 private:
  std::size_t collapse_pass() {
    std::vector<std::pair<double, detail::Edge>> short_edges;
    for (const detail::Edge& e : detail::collect_edges(blocks_)) {
      const double len = length(vertices_[e.a], vertices_[e.b]);
      if (len < min_edge_) short_edges.push_back({len, e});
    }
    std::sort(short_edges.begin(), short_edges.end(), [](const auto& l, const auto& r) {
      return std::tie(l.first, l.second.a, l.second.b) < std::tie(r.first, r.second.a, r.second.b);
    });
    index_blocks_of_vertices();
    std::vector<char> touched(vertices_.size(), 0);
    std::vector<std::uint32_t> remap(vertices_.size());
    std::iota(remap.begin(), remap.end(), 0U);
    std::size_t collapsed = 0;
    for (const auto& [len, e] : short_edges) {
      // One merge per vertex and pass: the remaining short edges are found again next pass.
      if (touched[e.a] || touched[e.b]) continue;
      const Target target = best_target(e.a, e.b);
      // Both indices get the new position so that later merges in this pass see it.
      vertices_[e.a] = vertices_[e.b] = target.position;
      locations_[e.a] = target.location;
      remap[e.b] = e.a;
      merged_into_[e.b] = e.a;
      touched[e.a] = touched[e.b] = 1;
      ++collapsed;
    }
    if (collapsed > 0) apply(remap);
    return collapsed;
  }

  void index_blocks_of_vertices() {
    first_block_.assign(vertices_.size() + 1, 0);
    for (const Block& block : blocks_) {
      for (const std::uint32_t v : block) ++first_block_[v + 1];
    }
    std::partial_sum(first_block_.begin(), first_block_.end(), first_block_.begin());
    block_of_.resize(first_block_.back());
    std::vector<std::uint32_t> fill(first_block_.begin(), first_block_.end() - 1);
    for (std::uint32_t b = 0; b < blocks_.size(); ++b) {
      for (const std::uint32_t v : blocks_[b]) block_of_[fill[v]++] = b;
    }
  }

  // The candidate that keeps the touched blocks most convex; the first (midpoint) on ties.
  Target best_target(std::uint32_t a, std::uint32_t b) const {
    const std::vector<Target> candidates = merge_candidates(a, b);
    Target best = candidates.front();
    double best_score = reflex_score(a, b, best.position);
    for (std::size_t i = 1; i < candidates.size() && best_score > 0; ++i) {
      const double score = reflex_score(a, b, candidates[i].position);
      if (score < best_score) {
        best_score = score;
        best = candidates[i];
      }
    }
    return best;
  }

  // Points along the edge, preferred first, kept on the outline where an end lies on it.
  std::vector<Target> merge_candidates(std::uint32_t a, std::uint32_t b) const {
    const Location la = locations_[a], lb = locations_[b];
    require(la.corner < 0 || lb.corner < 0,
            "min_edge_length (" + mm(min_edge_) + ") is longer than an outline segment");
    if (la.corner >= 0) return {{vertices_[a], la}};
    if (lb.corner >= 0) return {{vertices_[b], lb}};
    if (la.segment >= 0 && lb.segment >= 0 && la.segment != lb.segment) {
      return {shared_corner(la.segment, lb.segment, 0.5 * (vertices_[a] + vertices_[b]))};
    }
    const int segment = la.segment >= 0 ? la.segment : lb.segment;
    std::vector<Target> candidates;
    for (const double t : {0.5, 0.375, 0.625, 0.25, 0.75, 0.125, 0.875, 0.0, 1.0}) {
      const Point p = vertices_[a] + t * (vertices_[b] - vertices_[a]);
      candidates.push_back({segment >= 0 ? outline_.project(p, segment) : p, {segment, -1}});
    }
    return candidates;
  }

  // Largest right turn (radians, 0 if all convex) of the blocks around a and b with both at m.
  double reflex_score(std::uint32_t a, std::uint32_t b, Point m) const {
    double worst = 0;
    for (const std::uint32_t v : {a, b}) {
      for (std::uint32_t k = first_block_[v]; k < first_block_[v + 1]; ++k) {
        worst = std::max(worst, worst_turn(blocks_[block_of_[k]], a, b, m));
      }
    }
    return worst;
  }

  double worst_turn(const Block& block, std::uint32_t a, std::uint32_t b, Point m) const {
    Polygon polygon;
    for (const std::uint32_t v : block) {
      const Point p = (v == a || v == b) ? m : vertices_[v];
      if (polygon.empty() || p.x != polygon.back().x || p.y != polygon.back().y) {
        polygon.push_back(p);
      }
    }
    while (polygon.size() > 1 && polygon.front().x == polygon.back().x &&
           polygon.front().y == polygon.back().y) {
      polygon.pop_back();
    }
    if (polygon.size() < 3) return std::numeric_limits<double>::infinity();
    double worst = -std::numbers::pi;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Point in = polygon[i] - polygon[(i + polygon.size() - 1) % polygon.size()];
      const Point out = polygon[(i + 1) % polygon.size()] - polygon[i];
      worst = std::max(worst, -std::atan2(cross(in, out), dot(in, out)));
    }
    return worst;
  }

  // Collapses next to fixed outline corners can leave reflex corners: move those vertices (or
  // their neighbours) towards the centroid of their neighbours while that helps and keeps edges
  // long enough.
  void straighten_reflex_vertices() {
    index_blocks_of_vertices();
    for (int sweep = 0; sweep < kStraightenSweeps; ++sweep) {
      bool moved = false;
      for (const std::uint32_t v : reflex_vertices()) moved = straighten(v) || moved;
      if (!moved) break;
    }
  }

  // Vertices at reflex corners and their neighbours along the block.
  std::vector<std::uint32_t> reflex_vertices() const {
    std::vector<std::uint32_t> reflex;
    for (const Block& block : blocks_) {
      const std::size_t n = block.size();
      for (std::size_t i = 0; i < n; ++i) {
        const Point in = vertices_[block[i]] - vertices_[block[(i + n - 1) % n]];
        const Point out = vertices_[block[(i + 1) % n]] - vertices_[block[i]];
        if (cross(in, out) >= 0) continue;
        // The neighbours may be freer to move than the reflex vertex itself.
        reflex.insert(reflex.end(), {block[i], block[(i + n - 1) % n], block[(i + 1) % n]});
      }
    }
    std::sort(reflex.begin(), reflex.end());
    reflex.erase(std::unique(reflex.begin(), reflex.end()), reflex.end());
    return reflex;
  }

  // Smallest move towards the neighbour centroid or a chord midpoint (prev + next) / 2 of one of
  // its blocks that removes the reflex turn, else the best improvement.
  bool straighten(std::uint32_t v) {
    if (locations_[v].corner >= 0) return false;
    double best_score = reflex_score(v, v, vertices_[v]);
    Point best = vertices_[v];
    for (const Point goal : straightening_goals(v)) {
      for (const double t : {0.25, 0.5, 0.75, 1.0}) {
        Point p = vertices_[v] + t * (goal - vertices_[v]);
        if (locations_[v].segment >= 0) p = outline_.project(p, locations_[v].segment);
        const double score = reflex_score(v, v, p);
        if (score < best_score && shortest_edge_at(v, p) >= min_edge_) {
          best_score = score;
          best = p;
        }
        if (best_score <= 0) break;
      }
    }
    const bool moved = best.x != vertices_[v].x || best.y != vertices_[v].y;
    vertices_[v] = best;
    return moved;
  }

  std::vector<Point> straightening_goals(std::uint32_t v) const {
    std::vector<Point> goals{neighbour_centroid(v)};
    for (std::uint32_t k = first_block_[v]; k < first_block_[v + 1]; ++k) {
      const Block& block = blocks_[block_of_[k]];
      const auto i =
          static_cast<std::size_t>(std::find(block.begin(), block.end(), v) - block.begin());
      const Point next = vertices_[block[(i + 1) % block.size()]];
      const Point prev = vertices_[block[(i + block.size() - 1) % block.size()]];
      goals.push_back(0.5 * (next + prev));
    }
    return goals;
  }

  template <typename Visit>
  void for_each_neighbour(std::uint32_t v, Visit&& visit) const {
    for (std::uint32_t k = first_block_[v]; k < first_block_[v + 1]; ++k) {
      const Block& block = blocks_[block_of_[k]];
      const std::size_t i =
          static_cast<std::size_t>(std::find(block.begin(), block.end(), v) - block.begin());
      visit(block[(i + 1) % block.size()]);
      visit(block[(i + block.size() - 1) % block.size()]);
    }
  }

  Point neighbour_centroid(std::uint32_t v) const {
    Point sum;
    double count = 0;
    for_each_neighbour(v, [&](std::uint32_t w) {
      sum = sum + vertices_[w];
      count += 1;
    });
    return (1 / count) * sum;
  }

  double shortest_edge_at(std::uint32_t v, Point p) const {
    double shortest = std::numeric_limits<double>::infinity();
    for_each_neighbour(
        v, [&](std::uint32_t w) { shortest = std::min(shortest, length(p, vertices_[w])); });
    return shortest;
  }

  // Two outline vertices on adjacent segments can only meet at the corner between them.
  Target shared_corner(int s, int t, Point mid) const {
    const int n = outline_.corner_count();
    const int corner = (s + 1) % n == t ? t : ((t + 1) % n == s ? s : -1);
    if (corner < 0) return {mid, {}};
    return {outline_.corners()[static_cast<std::size_t>(corner)], {corner, corner}};
  }

  void apply(const std::vector<std::uint32_t>& remap) {
    for (Block& block : blocks_) {
      for (std::uint32_t& v : block) v = remap[v];
      remove_repeats(block);
      require(block.size() >= 3, too_large_message());
    }
  }

  double max_shift() const {
    double shift = 0;
    for (std::uint32_t v = 0; v < original_.size(); ++v) {
      std::uint32_t root = v;
      while (merged_into_[root] != root) root = merged_into_[root];
      shift = std::max(shift, length(original_[v], vertices_[root]));
    }
    return shift;
  }

  std::string too_large_message() const {
    return "min_edge_length (" + mm(min_edge_) + ") is too large for the block size: a block " +
           "degenerated while collapsing short edges";
  }

  std::vector<Point>& vertices_;
  Blocks& blocks_;
  const OutlinePolygon& outline_;
  double min_edge_;
  std::vector<Point> original_;
  std::vector<std::uint32_t> merged_into_;
  std::vector<Location> locations_;
  std::vector<std::uint32_t> first_block_;  // blocks of vertex v: block_of_[first_block_[v]...]
  std::vector<std::uint32_t> block_of_;
};

void require_proper_blocks(const Candidate& c, double min_edge) {
  for (const Block& block : c.blocks) {
    Block sorted = block;
    std::sort(sorted.begin(), sorted.end());
    const bool pinched = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    require(!pinched && detail::signed_area(c.vertices, block) > 0,
            "min_edge_length (" + mm(min_edge) + ") is too large for the block size: a block " +
                "has no area left after collapsing short edges");
  }
}

// Cells with fewer than three edges of at least min_edge_length would vanish in the collapse.
bool is_thin(const Polygon& cell, double min_edge) {
  int long_edges = 0;
  for (std::size_t i = 0; i < cell.size(); ++i) {
    if (length(cell[i], cell[(i + 1) % cell.size()]) >= min_edge) ++long_edges;
  }
  return long_edges < 3;
}

// Local Lloyd steps for thin cells only, so that the edge collapse keeps every block.
std::vector<Polygon> relax_thin_cells(Polygon& seeds, const OutlinePolygon& outline,
                                      double min_edge, std::size_t& relaxed) {
  std::vector<char> moved(seeds.size(), 0);
  std::vector<Polygon> cells = voronoi_cells(seeds, outline);
  for (int sweep = 0; sweep < kThinCellSweeps; ++sweep) {
    bool any = false;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (!is_thin(cells[i], min_edge)) continue;
      seeds[i] = polygon_centroid(cells[i]);
      moved[i] = 1;
      any = true;
    }
    if (!any) break;
    cells = voronoi_cells(seeds, outline);
  }
  relaxed = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  return cells;
}

double mean_edge_length(const Candidate& c) {
  const std::vector<detail::Edge> edges = detail::collect_edges(c.blocks);
  double sum = 0;
  for (const detail::Edge& e : edges) sum += length(c.vertices[e.a], c.vertices[e.b]);
  return sum / static_cast<double>(edges.size());
}

Candidate build_candidate(const OutlinePolygon& outline, const TessellationSettings& s,
                          std::size_t count) {
  Polygon seeds = random_seeds(outline, s.seed, count);
  for (int sweep = 0; sweep < s.lloyd_iterations; ++sweep) seeds = lloyd_step(seeds, outline);
  std::size_t relaxed = 0;
  std::vector<Polygon> cells = s.min_edge_length > 0
                                   ? relax_thin_cells(seeds, outline, s.min_edge_length, relaxed)
                                   : voronoi_cells(seeds, outline);
  const double tolerance = kWeldTolerance * outline.extent();
  Candidate c = weld_cells(cells, tolerance);
  if (s.min_edge_length > 0) {
    c.collapse = EdgeCollapser(c, outline, s.min_edge_length, tolerance).run();
    c.collapse.relaxed_seeds = relaxed;
    require_proper_blocks(c, s.min_edge_length);
  }
  return c;
}

// Mean edge ~ k N^slope: secant steps in log-log space, slope -1/2 until two samples exist.
double next_count(const std::vector<std::pair<double, double>>& samples, double target) {
  double slope = -0.5;
  if (samples.size() >= 2) {
    const auto& [n0, m0] = samples[samples.size() - 2];
    const auto& [n1, m1] = samples.back();
    if (n1 != n0)
      slope =
          std::clamp((std::log(m1) - std::log(m0)) / (std::log(n1) - std::log(n0)), -1.0, -0.25);
  }
  const auto& [n, m] = samples.back();
  const double step = std::clamp((std::log(target) - std::log(m)) / slope, -1.5, 1.5);
  return std::exp(std::log(n) + step);
}

Candidate build_for_mean_edge(const OutlinePolygon& outline, const TessellationSettings& s) {
  const double target = s.mean_edge_length;
  double count = outline.area() * std::pow(kPoissonEdgeFactor / target, 2);
  require(count >= 2, "mean_edge_length (" + mm(target) + ") gives fewer than 2 blocks");
  Candidate best;
  double best_error = std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, double>> samples;
  for (int pass = 0; pass < kCountPasses; ++pass) {
    const auto n = static_cast<std::size_t>(std::max(2.0, std::round(count)));
    require(n <= kMaxBlocks, "mean_edge_length is too small (too many blocks)");
    if (!samples.empty() && static_cast<double>(n) == samples.back().first) break;
    Candidate c = build_candidate(outline, s, n);
    const double mean_edge = mean_edge_length(c);
    samples.push_back({static_cast<double>(n), mean_edge});
    const double error = std::abs(mean_edge / target - 1);
    if (error < best_error) {
      best_error = error;
      best = std::move(c);
    }
    if (error < kCountTolerance) break;
    count = next_count(samples, target);
  }
  return best;
}

// Blocks along the Hilbert curve, vertices in order of first use: neighbours near in memory.
// Per-block tags (if any) follow their blocks.
void renumber_along_hilbert(std::vector<Point>& vertices, Blocks& blocks,
                            std::vector<std::int32_t>& tags) {
  std::vector<Point> centroids;
  centroids.reserve(blocks.size());
  for (const Block& block : blocks) centroids.push_back(detail::centroid(vertices, block));
  constexpr auto unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> new_index(vertices.size(), unused);
  std::vector<Point> new_vertices;
  new_vertices.reserve(vertices.size());
  Blocks new_blocks;
  new_blocks.reserve(blocks.size());
  std::vector<std::int32_t> new_tags;
  for (const std::size_t b : hilbert_order(centroids)) {
    if (!tags.empty()) new_tags.push_back(tags[b]);
    Block block = std::move(blocks[b]);
    for (std::uint32_t& v : block) {
      if (new_index[v] == unused) {
        new_index[v] = static_cast<std::uint32_t>(new_vertices.size());
        new_vertices.push_back(vertices[v]);
      }
      v = new_index[v];
    }
    new_blocks.push_back(std::move(block));
  }
  vertices = std::move(new_vertices);
  blocks = std::move(new_blocks);
  tags = std::move(new_tags);
}

// Disc segments ~ half the mean edge, but never shorter than twice min_edge_length.
double disc_segment_length(const TessellationSettings& s) {
  const Outline& o = s.outline;
  const double disc_area = std::numbers::pi * o.diameter * o.diameter / 4;
  const double mean_edge =
      s.mean_edge_length > 0
          ? s.mean_edge_length
          : kPoissonEdgeFactor * std::sqrt(disc_area / std::max(s.block_count, 1));
  return std::max(mean_edge / 2, 2 * s.min_edge_length);
}

}  // namespace

namespace detail {

double outline_segment_length(const TessellationSettings& settings) {
  return disc_segment_length(settings);
}

Polygon random_points_in(const Polygon& region, std::uint64_t seed, std::size_t count) {
  Point lo = region.front(), hi = region.front();
  for (const Point p : region) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  const auto inside = [&](Point p) {
    for (std::size_t k = 0; k < region.size(); ++k)
      if (cross(region[(k + 1) % region.size()] - region[k], p - region[k]) <= 0) return false;
    return true;
  };
  UnitRandom random(seed);
  Polygon points;
  points.reserve(count);
  while (points.size() < count) {
    const Point p{lo.x + random.next() * (hi.x - lo.x), lo.y + random.next() * (hi.y - lo.y)};
    if (inside(p)) points.push_back(p);
  }
  return points;
}

std::vector<Polygon> clipped_voronoi(const Polygon& seeds, const Polygon& region) {
  const Neighbours neighbours = delaunay_neighbours(seeds);
  HalfPlaneClipper clip;
  std::vector<Polygon> cells(seeds.size());
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const Point p = seeds[i];
    Polygon cell;
    cell.reserve(region.size());
    for (const Point v : region) cell.push_back(v - p);
    for (const std::uint32_t j : neighbours[i]) {
      const Point n = seeds[j] - p;
      clip(cell, n, dot(n, n) / 2);
    }
    for (Point& v : cell) v = v + p;
    cells[i] = std::move(cell);
  }
  return cells;
}

Point area_centroid(const Polygon& polygon) {
  return polygon_centroid(polygon);
}

void weld_polygons(const std::vector<Polygon>& polygons, double tolerance,
                   std::vector<Point>& vertices, Blocks& blocks) {
  Candidate c = weld_cells(polygons, tolerance);
  vertices = std::move(c.vertices);
  blocks = std::move(c.blocks);
}

Tessellation assemble(const std::vector<Polygon>& cells, std::vector<std::int32_t> tags,
                      const TessellationSettings& settings, double segment_length) {
  const OutlinePolygon outline(settings.outline, segment_length);
  const double tolerance = kWeldTolerance * outline.extent();
  Candidate c = weld_cells(cells, tolerance);
  split_t_junctions(c.vertices, c.blocks, tolerance);
  if (settings.min_edge_length > 0) {
    c.collapse = EdgeCollapser(c, outline, settings.min_edge_length, tolerance).run();
    require_proper_blocks(c, settings.min_edge_length);
  }
  renumber_along_hilbert(c.vertices, c.blocks, tags);
  Tessellation result;
  result.report = build_report(c.vertices, c.blocks, outline.area(), c.collapse);
  result.vertices = std::move(c.vertices);
  result.blocks = std::move(c.blocks);
  result.block_grain = std::move(tags);
  return result;
}

}  // namespace detail

Tessellation tessellate(const TessellationSettings& settings) {
  validate(settings);
  const OutlinePolygon outline(settings.outline, disc_segment_length(settings));
  Candidate c =
      settings.block_count > 0
          ? build_candidate(outline, settings, static_cast<std::size_t>(settings.block_count))
          : build_for_mean_edge(outline, settings);
  std::vector<std::int32_t> no_tags;
  renumber_along_hilbert(c.vertices, c.blocks, no_tags);
  Tessellation result;
  result.report = detail::build_report(c.vertices, c.blocks, outline.area(), c.collapse);
  result.vertices = std::move(c.vertices);
  result.blocks = std::move(c.blocks);
  return result;
}

}  // namespace vorodec::geometry
