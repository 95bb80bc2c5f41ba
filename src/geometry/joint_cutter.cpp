// Joint sets and fracture traces cutting a tessellation (include/vorodec/geometry/joints.hpp).
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "tessellation_internal.hpp"
#include "vorodec/geometry/joints.hpp"

namespace vorodec::geometry {

namespace {

using detail::Polygon;

// SplitMix64: the same draws on every platform (std's distributions are not specified exactly).
class Draws {
 public:
  explicit Draws(std::uint64_t seed) : state_(seed) {}
  double uniform() {  // in [0, 1)
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  double normal() {  // Box-Muller
    const double u = 1.0 - uniform(), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
  }

 private:
  std::uint64_t state_;
};

struct Box {
  Point lo, hi;
  Point centre() const { return 0.5 * (lo + hi); }
  double half_diagonal() const { return 0.5 * std::hypot(hi.x - lo.x, hi.y - lo.y); }
};

Box outline_box(const Outline& o) {
  if (o.kind == OutlineKind::disc) return {{0, 0}, {o.diameter, o.diameter}};
  return {{0, 0}, {o.width, o.height}};
}

Point direction(double deg) {
  const double r = deg * std::numbers::pi / 180.0;
  return {std::cos(r), std::sin(r)};
}

// The traces along one joint line through p with direction d, reaching `reach` either side of
// the point of the line nearest to the box's centre.
void add_line(const JointSetGeometry& g, const Box& box, Point p, Point d, std::int32_t set,
              Draws& draws, std::vector<JointTrace>& out) {
  const double reach = 2.0 * box.half_diagonal();
  const Point mid = p + dot(box.centre() - p, d) * d;
  if (g.trace <= 0) {
    out.push_back({mid - reach * d, mid + reach * d, set});
    return;
  }
  const double period = g.trace + g.gap;
  for (double s = -reach - draws.uniform() * period; s < reach; s += period)
    out.push_back({mid + s * d, mid + (s + g.trace) * d, set});
}

// The two points where the line {x : dot(n, x) = offset} crosses a polygon, and the edges they
// lie on (edge i runs from corner i to i + 1); false unless it crosses exactly twice (a polygon
// that snapping made slightly concave still splits in two). A crossing within `snap` of an edge's
// end (rounding) is that corner.
struct Crossing {
  Point p[2];
  std::size_t edge[2];
};
bool crossing(const Polygon& poly, Point n, double offset, double tolerance, double snap,
              Crossing& c) {
  int found = 0;
  const std::size_t m = poly.size();
  // A run of corners on the line may cross at either end: [start corner, end corner].
  std::size_t run_start[2] = {0, 0};
  bool run[2] = {false, false};
  for (std::size_t i = 0; i < m; ++i) {
    const Point u = poly[i], v = poly[(i + 1) % m];
    const double su = dot(n, u) - offset, sv = dot(n, v) - offset;
    const bool u_in = su < -tolerance, v_in = sv < -tolerance;
    const bool u_out = su > tolerance, v_out = sv > tolerance;
    Point p;
    std::size_t start = i;
    if ((u_in && v_out) || (u_out && v_in)) {
      p = u + su / (su - sv) * (v - u);
      if (detail::length(p, u) < snap)
        p = u;
      else if (detail::length(p, v) < snap)
        p = v;
    } else if (!u_in && !u_out && (v_in || v_out)) {
      // u ends a run of corners on the line: a crossing if the corners before the run and after
      // it lie either side.
      double sw = 0;
      for (std::size_t k = 1; k < m && std::abs(sw) <= tolerance; ++k) {
        sw = dot(n, poly[(i + m - k) % m]) - offset;
        if (std::abs(sw) <= tolerance) start = (i + m - k) % m;
      }
      if (!((sw < -tolerance && v_out) || (sw > tolerance && v_in))) continue;
      p = u;
    } else {
      continue;
    }
    if (found == 2) return false;
    run[found] = start != i;
    run_start[found] = start;
    c.p[found] = p;
    c.edge[found++] = i;
  }
  if (found != 2) return false;
  // The chord runs from the run's corner nearest the other crossing: the run stays on one piece's
  // side instead of folding back over the chord.
  for (int k = 0; k < 2; ++k) {
    if (!run[k]) continue;
    const Point first = poly[run_start[k]], other = c.p[1 - k];
    if (detail::length(first, other) < detail::length(c.p[k], other)) {
      c.p[k] = first;
      c.edge[k] = (run_start[k] + m - 1) % m;
    }
  }
  return detail::length(c.p[0], c.p[1]) > snap;
}

// The polygon from crossing `from` to crossing `to` along its corners, without repeated points.
Polygon piece(const Polygon& poly, const Crossing& c, int from, int to) {
  Polygon out{c.p[from]};
  const std::size_t m = poly.size();
  const auto add = [&](Point q) {
    if (q.x != out.back().x || q.y != out.back().y) out.push_back(q);
  };
  for (std::size_t i = (c.edge[from] + 1) % m;; i = (i + 1) % m) {
    add(poly[i]);
    if (i == c.edge[to]) break;
  }
  add(c.p[to]);
  if (out.size() > 1 && out.back().x == out.front().x && out.back().y == out.front().y)
    out.pop_back();
  return out;
}

// Moves the vertices within `snap` of a trace onto it, so that a joint passing near a block
// corner stays straight and leaves no sliver: an interior vertex straight to it, an outline
// vertex along the outline (a corner of the outline stays).
void snap_to_traces(std::vector<Point>& vertices, const detail::Blocks& blocks,
                    std::span<const JointTrace> traces, double snap) {
  // Per vertex on the outline: its two outline neighbours (-1: interior).
  std::vector<std::int64_t> first(vertices.size(), -1), second(vertices.size(), -1);
  const auto link = [&](std::uint32_t v, std::uint32_t w) {
    (first[v] < 0 ? first[v] : second[v]) = w;
  };
  for (const detail::Edge& e : detail::collect_edges(blocks))
    if (e.uses == 1) link(e.a, e.b), link(e.b, e.a);
  for (const JointTrace& t : traces) {
    const Point d0 = t.b - t.a;
    const double len = std::sqrt(dot(d0, d0));
    const Point d = (1.0 / len) * d0, n{-d.y, d.x};
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      Point& v = vertices[i];
      const double s = dot(n, v - t.a), along = dot(d, v - t.a);
      if (std::abs(s) >= snap || along < -snap || along > len + snap) continue;
      if (first[i] < 0 || second[i] < 0) {
        v = v - s * n;
        continue;
      }
      const Point p = vertices[static_cast<std::size_t>(first[i])];
      const Point q = vertices[static_cast<std::size_t>(second[i])];
      const Point side = q - p;
      const double along_side = dot(n, side);
      if (std::abs(cross(side, v - p)) > 1e-9 * dot(side, side) || along_side == 0) continue;
      const Point moved = v - (s / along_side) * side;  // on the line, along the outline
      if (detail::length(moved, v) < snap) v = moved;
    }
  }
}

// Whether edge (u, v) lies on the trace, within `tolerance`.
bool on_trace(Point u, Point v, const JointTrace& c, double tolerance) {
  const Point d0 = c.b - c.a;
  const double len = std::sqrt(dot(d0, d0));
  const Point d = (1.0 / len) * d0, n{-d.y, d.x};
  for (const Point p : {u, v, 0.5 * (u + v)}) {
    const double along = dot(d, p - c.a);
    if (std::abs(dot(n, p - c.a)) > tolerance || along < -tolerance || along > len + tolerance)
      return false;
  }
  return true;
}

}  // namespace

std::vector<JointTrace> joint_set_traces(const JointSetGeometry& g, const Outline& outline,
                                         std::int32_t set, std::uint64_t seed) {
  const Box box = outline_box(outline);
  const Point d0 = direction(g.dip_deg), n0{-d0.y, d0.x};
  const double centre = dot(n0, box.centre() - g.origin), reach = box.half_diagonal();
  Draws draws(seed ^ (0x51ed270b27a3c1f5ull * static_cast<std::uint64_t>(set + 1)));
  const auto step = [&] {
    return std::max(g.spacing + g.spacing_spread * draws.normal(), 0.1 * g.spacing);
  };
  std::vector<double> offsets{0.0};
  for (double o = step(); o <= centre + reach; o += step()) offsets.push_back(o);
  for (double o = -step(); o >= centre - reach; o -= step()) offsets.push_back(o);
  std::sort(offsets.begin(), offsets.end());
  std::vector<JointTrace> traces;
  for (const double o : offsets) {
    if (std::abs(o - centre) > reach) continue;
    const double dip = g.dip_deg + (g.dip_spread > 0 ? g.dip_spread * draws.normal() : 0.0);
    add_line(g, box, g.origin + o * n0, direction(dip), set, draws, traces);
  }
  return traces;
}

Tessellation cut_by_joints(const Tessellation& intact, std::span<const JointTrace> traces,
                           const TessellationSettings& settings) {
  const Box box = outline_box(settings.outline);
  const double tolerance = 1e-9 * 2.0 * box.half_diagonal();
  std::vector<Point> vertices = intact.vertices;
  snap_to_traces(vertices, intact.blocks, traces, 0.2 * intact.report.edge_mean);
  const double snap = 1e3 * tolerance;
  // A small block with every corner near a joint lies flat on it after snapping: it goes, and
  // its neighbours meet on the joint.
  std::vector<Polygon> cells;
  for (const auto& b : intact.blocks) {
    if (detail::signed_area(vertices, b) <= tolerance * tolerance) continue;
    Polygon p;
    for (const auto v : b) p.push_back(vertices[v]);
    cells.push_back(std::move(p));
  }
  for (const JointTrace& t : traces) {
    const Point d0 = t.b - t.a;
    const double len = std::sqrt(dot(d0, d0));
    if (!(len > tolerance)) continue;
    const Point d = (1.0 / len) * d0, n{-d.y, d.x};
    const double offset = dot(n, t.a);
    const std::size_t count = cells.size();
    for (std::size_t i = 0; i < count; ++i) {
      Crossing c;
      if (!crossing(cells[i], n, offset, tolerance, snap, c)) continue;
      const double s0 = dot(d, c.p[0] - t.a), s1 = dot(d, c.p[1] - t.a);
      if (std::min(s0, s1) < -snap || std::max(s0, s1) > len + snap) continue;
      Polygon first = piece(cells[i], c, 0, 1), second = piece(cells[i], c, 1, 0);
      if (first.size() < 3 || second.size() < 3) continue;
      cells[i] = std::move(first);
      cells.push_back(std::move(second));
    }
  }
  // Snapping leaves the cut no edge shorter than the snap distance but where joints cross or
  // end near one another: nothing is collapsed (it would bend the joints).
  TessellationSettings s = settings;
  s.min_edge_length = 0;
  Tessellation out = detail::assemble(cells, {}, s, detail::outline_segment_length(settings));
  // Label the shared edges that lie on a trace.
  const double label = 1e3 * tolerance;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> first_block;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> pair_index;
  for (std::uint32_t bi = 0; bi < out.blocks.size(); ++bi) {
    const auto& b = out.blocks[bi];
    for (std::size_t k = 0; k < b.size(); ++k) {
      const std::uint32_t u = b[k], v = b[(k + 1) % b.size()];
      const auto [it, fresh] = first_block.emplace(std::minmax(u, v), bi);
      if (fresh) continue;
      const Point pu = out.vertices[u], pv = out.vertices[v];
      const Point ca = detail::centroid(out.vertices, out.blocks[it->second]);
      const Point cb = detail::centroid(out.vertices, b);
      for (const JointTrace& c : traces) {
        // On the trace, and between blocks on either side of it (not an intact edge near it).
        const Point n{c.a.y - c.b.y, c.b.x - c.a.x};
        if (!on_trace(pu, pv, c, label) || dot(n, ca - c.a) * dot(n, cb - c.a) >= 0) continue;
        const std::pair<std::uint32_t, std::uint32_t> blocks{std::min(it->second, bi),
                                                             std::max(it->second, bi)};
        const auto [p, added] = pair_index.emplace(blocks, out.joint_edges.size());
        if (added) out.joint_edges.push_back({blocks.first, blocks.second, c.set, 0.0});
        out.joint_edges[p->second].length += detail::length(pu, pv);
        break;
      }
    }
  }
  return out;
}

}  // namespace vorodec::geometry
