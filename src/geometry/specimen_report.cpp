// Specimen statistics and the human-readable report; pure geometry on the final vertex table.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "tessellation_internal.hpp"
#include "vorodec/geometry/tessellation.hpp"

namespace vorodec::geometry {
namespace detail {
namespace {

constexpr double kSliverAspectRatio = 5.0;
constexpr double kSliverAreaFraction = 0.05;
constexpr double kSmallAngleDeg = 20.0;
constexpr double kShortEdgeFraction = 0.01;
constexpr double kMm = 1e3;
constexpr double kMm2 = 1e6;

template <typename... Args>
std::string printf_string(const char* format, Args... args) {
  const int size = std::snprintf(nullptr, 0, format, args...);
  std::string text(static_cast<std::size_t>(std::max(size, 0)), '\0');
  std::snprintf(text.data(), text.size() + 1, format, args...);
  return text;
}

// Second moments about the centroid; computed relative to vertex 0 to keep round-off small.
struct Moments {
  double area = 0, sxx = 0, syy = 0, sxy = 0;
};

Moments central_moments(const std::vector<Point>& vertices, const Block& block) {
  const Point origin = vertices[block.front()];
  double area = 0, cx = 0, cy = 0, ixx = 0, iyy = 0, ixy = 0;
  for (std::size_t i = 0; i < block.size(); ++i) {
    const Point p = vertices[block[i]] - origin;
    const Point q = vertices[block[(i + 1) % block.size()]] - origin;
    const double a = cross(p, q);
    area += a / 2;
    cx += (p.x + q.x) * a / 6;
    cy += (p.y + q.y) * a / 6;
    ixx += (p.x * p.x + p.x * q.x + q.x * q.x) * a / 12;
    iyy += (p.y * p.y + p.y * q.y + q.y * q.y) * a / 12;
    ixy += (p.x * q.y + 2 * p.x * p.y + 2 * q.x * q.y + q.x * p.y) * a / 24;
  }
  if (area <= 0) return {area, 0, 0, 0};
  cx /= area;
  cy /= area;
  return {area, ixx - area * cx * cx, iyy - area * cy * cy, ixy - area * cx * cy};
}

// Ratio of the principal radii of gyration: 1 for a regular polygon, a/b for an a x b rectangle.
double aspect_ratio(const std::vector<Point>& vertices, const Block& block) {
  const Moments m = central_moments(vertices, block);
  const double mean = (m.sxx + m.syy) / 2;
  const double radius = std::hypot((m.sxx - m.syy) / 2, m.sxy);
  const double smallest = mean - radius;
  if (smallest <= 0) return std::numeric_limits<double>::infinity();
  return std::sqrt((mean + radius) / smallest);
}

// Interior angle at each vertex of a CCW polygon, degrees.
std::vector<double> interior_angles(const std::vector<Point>& vertices, const Block& block) {
  std::vector<double> angles;
  const std::size_t n = block.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point v = vertices[block[i]];
    const Point next = vertices[block[(i + 1) % n]] - v;
    const Point prev = vertices[block[(i + n - 1) % n]] - v;
    double angle = std::atan2(cross(next, prev), dot(next, prev));
    if (angle < 0) angle += 2 * std::numbers::pi;
    angles.push_back(angle * 180 / std::numbers::pi);
  }
  return angles;
}

void fill_edge_statistics(const std::vector<Point>& vertices, const std::vector<Edge>& edges,
                          SpecimenReport& report) {
  double sum = 0;
  report.edge_min = std::numeric_limits<double>::infinity();
  for (const Edge& e : edges) {
    const double len = length(vertices[e.a], vertices[e.b]);
    report.edge_min = std::min(report.edge_min, len);
    report.edge_max = std::max(report.edge_max, len);
    sum += len;
    (e.uses == 1 ? report.boundary_edges : report.shared_edges) += 1;
  }
  report.edge_mean = edges.empty() ? 0 : sum / static_cast<double>(edges.size());
  if (edges.empty()) report.edge_min = 0;
}

void fill_area_statistics(const std::vector<Point>& vertices, const Blocks& blocks,
                          SpecimenReport& report) {
  double sum = 0;
  report.area_min = std::numeric_limits<double>::infinity();
  for (const Block& block : blocks) {
    const double area = signed_area(vertices, block);
    report.area_min = std::min(report.area_min, area);
    report.area_max = std::max(report.area_max, area);
    sum += area;
  }
  report.area_mean = blocks.empty() ? 0 : sum / static_cast<double>(blocks.size());
  if (blocks.empty()) report.area_min = 0;
}

void add_collapse_warning(const CollapseSummary& collapse, SpecimenReport& report) {
  report.edges_collapsed = collapse.edges;
  if (collapse.relaxed_seeds > 0) {
    report.warnings.push_back(printf_string(
        "moved %zu seeds to their cell centroids (cells too thin for min_edge_length %.4g mm)",
        collapse.relaxed_seeds, collapse.min_edge_length * kMm));
  }
  if (collapse.edges == 0) return;
  report.warnings.push_back(
      printf_string("collapsed %zu edges shorter than %.4g mm (max vertex shift %.3g mm)",
                    collapse.edges, collapse.min_edge_length * kMm, collapse.max_shift * kMm));
}

void add_shape_warnings(const std::vector<Point>& vertices, const Blocks& blocks,
                        SpecimenReport& report) {
  std::size_t slivers = 0, small_angles = 0;
  double worst_aspect = 0;
  report.smallest_angle_deg = blocks.empty() ? 0 : 360.0;
  for (const Block& block : blocks) {
    const double aspect = aspect_ratio(vertices, block);
    worst_aspect = std::max(worst_aspect, aspect);
    const bool tiny = signed_area(vertices, block) < kSliverAreaFraction * report.area_mean;
    if (aspect > kSliverAspectRatio || tiny) ++slivers;
    for (const double angle : interior_angles(vertices, block)) {
      report.smallest_angle_deg = std::min(report.smallest_angle_deg, angle);
      if (angle < kSmallAngleDeg) ++small_angles;
    }
  }
  if (slivers > 0) {
    report.warnings.push_back(printf_string(
        "%zu sliver blocks (aspect ratio > %.0f or area < %.0f%% of mean; worst aspect %.3g)",
        slivers, kSliverAspectRatio, kSliverAreaFraction * 100, worst_aspect));
  }
  if (small_angles > 0) {
    report.warnings.push_back(printf_string(
        "%zu block corners with interior angle < %.0f degrees (smallest %.3g degrees)",
        small_angles, kSmallAngleDeg, report.smallest_angle_deg));
  }
}

// Very short edges and vertices joining four or more blocks make contact detection ambiguous.
void add_vertex_warnings(const std::vector<Point>& vertices, const Blocks& blocks,
                         const std::vector<Edge>& edges, SpecimenReport& report) {
  const double short_limit = kShortEdgeFraction * report.edge_mean;
  const auto short_edges = std::count_if(edges.begin(), edges.end(), [&](const Edge& e) {
    return length(vertices[e.a], vertices[e.b]) < short_limit;
  });
  if (short_edges > 0) {
    report.warnings.push_back(
        printf_string("%zu near-degenerate vertex pairs (edges < %.3g mm, 1%% of mean edge); "
                      "set min_edge_length to collapse them",
                      static_cast<std::size_t>(short_edges), short_limit * kMm));
  }
  std::vector<std::uint32_t> valence(vertices.size(), 0);
  for (const Block& block : blocks) {
    for (const std::uint32_t v : block) ++valence[v];
  }
  const auto crowded =
      std::count_if(valence.begin(), valence.end(), [](std::uint32_t n) { return n >= 4; });
  if (crowded > 0) {
    report.warnings.push_back(
        printf_string("%zu vertices shared by 4 or more blocks (corner-to-corner contacts)",
                      static_cast<std::size_t>(crowded)));
  }
}

}  // namespace

double length(Point a, Point b) {
  return std::sqrt(dot(b - a, b - a));
}

std::vector<Edge> collect_edges(const Blocks& blocks) {
  // Packed (min, max) keys sort much faster than structs.
  std::vector<std::uint64_t> keys;
  for (const Block& block : blocks) {
    for (std::size_t i = 0; i < block.size(); ++i) {
      const std::uint64_t a = block[i], b = block[(i + 1) % block.size()];
      keys.push_back(std::min(a, b) << 32 | std::max(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<Edge> unique;
  unique.reserve(keys.size() / 2 + 1);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i > 0 && keys[i] == keys[i - 1]) {
      ++unique.back().uses;
    } else {
      unique.push_back({static_cast<std::uint32_t>(keys[i] >> 32),
                        static_cast<std::uint32_t>(keys[i] & 0xffffffffU), 1});
    }
  }
  return unique;
}

double signed_area(const std::vector<Point>& vertices, const Block& block) {
  const Point origin = vertices[block.front()];
  double twice = 0;
  for (std::size_t i = 1; i + 1 < block.size(); ++i) {
    twice += cross(vertices[block[i]] - origin, vertices[block[i + 1]] - origin);
  }
  return twice / 2;
}

Point centroid(const std::vector<Point>& vertices, const Block& block) {
  const Point origin = vertices[block.front()];
  double twice = 0;
  Point sum;
  for (std::size_t i = 1; i + 1 < block.size(); ++i) {
    const Point p = vertices[block[i]] - origin;
    const Point q = vertices[block[i + 1]] - origin;
    const double a = cross(p, q);
    twice += a;
    sum = sum + (a / 3) * (p + q);
  }
  return origin + (1 / twice) * sum;
}

SpecimenReport build_report(const std::vector<Point>& vertices, const Blocks& blocks,
                            double outline_area, const CollapseSummary& collapse) {
  SpecimenReport report;
  report.blocks = blocks.size();
  report.outline_area = outline_area;
  const std::vector<Edge> edges = collect_edges(blocks);
  fill_edge_statistics(vertices, edges, report);
  fill_area_statistics(vertices, blocks, report);
  add_collapse_warning(collapse, report);
  add_shape_warnings(vertices, blocks, report);
  add_vertex_warnings(vertices, blocks, edges, report);
  return report;
}

}  // namespace detail

SpecimenReport describe_specimen(const Tessellation& tess) {
  double area = 0.0;
  for (const auto& b : tess.blocks) area += detail::signed_area(tess.vertices, b);
  return detail::build_report(tess.vertices, tess.blocks, area, detail::CollapseSummary{});
}

std::string format_report(const SpecimenReport& r) {
  using detail::kMm;
  using detail::kMm2;
  using detail::printf_string;
  std::string text = "Specimen geometry\n";
  text += printf_string("  blocks:            %zu\n", r.blocks);
  text += printf_string("  outline area:      %.6g mm^2\n", r.outline_area * kMm2);
  text += printf_string("  edges:             %zu shared (%zu point contacts), %zu on outline\n",
                        r.shared_edges, 2 * r.shared_edges, r.boundary_edges);
  text += printf_string("  edge length:       min %.4g  mean %.4g  max %.4g mm\n", r.edge_min * kMm,
                        r.edge_mean * kMm, r.edge_max * kMm);
  text += printf_string("  block area:        min %.4g  mean %.4g  max %.4g mm^2\n",
                        r.area_min * kMm2, r.area_mean * kMm2, r.area_max * kMm2);
  text += printf_string("  smallest angle:    %.3g degrees\n", r.smallest_angle_deg);
  text += printf_string("  edges collapsed:   %zu\n", r.edges_collapsed);
  if (r.warnings.empty()) return text + "  warnings:          none\n";
  text += printf_string("  warnings (%zu):\n", r.warnings.size());
  for (const std::string& w : r.warnings) text += "    - " + w + "\n";
  return text;
}

}  // namespace vorodec::geometry
