#include "vorodec/loading/quiet_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vorodec::loading {

using model::Point;

std::vector<BoundaryEdge> outline_edges(const model::Model& m, Side side) {
  const auto& bl = m.blocks;
  double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  for (std::uint32_t b = 0; b < bl.size(); ++b)
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c) {
      if (bl.group[b] != model::Group::specimen) break;
      const Point p = bl.to_world(b, bl.corner[c]);
      x0 = std::min(x0, p.x);
      x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y);
      y1 = std::max(y1, p.y);
    }
  const double tol = 1e-9 * std::max(x1 - x0, y1 - y0);
  const auto on = [&](Point p) {
    switch (side) {
      case Side::left:
        return std::abs(p.x - x0) < tol;
      case Side::right:
        return std::abs(p.x - x1) < tol;
      case Side::bottom:
        return std::abs(p.y - y0) < tol;
      case Side::top:
        return std::abs(p.y - y1) < tol;
    }
    return false;
  };
  std::vector<BoundaryEdge> edges;
  for (std::uint32_t b = 0; b < bl.size(); ++b)
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c)
      if (bl.group[b] == model::Group::specimen && on(bl.to_world(b, bl.corner[c])) &&
          on(bl.to_world(b, bl.corner[bl.next_corner(b, c)])))
        edges.push_back({b, c});
  return edges;
}

QuietBoundary::QuietBoundary(std::vector<BoundaryEdge> edges, QuietSettings s)
    : edges_(std::move(edges)), s_(s) {}

void QuietBoundary::set_input(std::vector<BoundaryEdge> edges, InputHistory input) {
  input_edges_ = std::move(edges);
  input_ = std::move(input);
}

void QuietBoundary::clear_loads(model::Model& m) const {
  auto& bl = m.blocks;
  for (const auto* list : {&edges_, &input_edges_})
    for (const BoundaryEdge& e : *list) bl.fx[e.block] = bl.fy[e.block] = bl.moment[e.block] = 0.0;
}

void QuietBoundary::apply(model::Model& m, double t) const {
  auto& bl = m.blocks;
  const double zp = s_.density * s_.p_wave_speed, zs = s_.density * s_.s_wave_speed;
  const InputVelocity in = input_ ? input_(t) : InputVelocity{0.0, 0.0};
  const auto add = [&](const BoundaryEdge& e, bool input) {
    const std::uint32_t b = e.block;
    const Point p0 = bl.to_world(b, bl.corner[e.corner]);
    const Point p1 = bl.to_world(b, bl.corner[bl.next_corner(b, e.corner)]);
    const Point d = p1 - p0, mid = 0.5 * (p0 + p1);
    const double len = std::sqrt(dot(d, d));
    const Point tan = (1.0 / len) * d, n{tan.y, -tan.x};  // n outward (counter-clockwise)
    const Point r = mid - Point{bl.x[b], bl.y[b]};
    const Point v{bl.vx[b] - bl.omega[b] * r.y, bl.vy[b] + bl.omega[b] * r.x};
    double fn = -zp * dot(v, n) * len, fs = -zs * dot(v, tan) * len;  // dashpots
    if (input) {  // 2 rho c v_in, inward (-n) for the normal part
      fn -= 2.0 * zp * in.normal * len;
      fs += 2.0 * zs * in.shear * len;
    }
    const Point f = fn * n + fs * tan;
    bl.fx[b] += f.x;
    bl.fy[b] += f.y;
    bl.moment[b] += r.x * f.y - r.y * f.x;
  };
  for (const BoundaryEdge& e : edges_) add(e, false);
  for (const BoundaryEdge& e : input_edges_) add(e, true);
}

}  // namespace vorodec::loading
