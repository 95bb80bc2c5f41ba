#include "vorodec/loading/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vorodec::loading {

using model::Group;
using model::Point;

SpecimenBoundary::SpecimenBoundary(const model::Model& model) {
  const auto& bl = model.blocks;
  double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    if (bl.group[b] == Group::top_platen) top_ = static_cast<int>(b);
    if (bl.group[b] == Group::bottom_platen) bottom_ = static_cast<int>(b);
    if (bl.group[b] == Group::incident_bar) in_bars_ = true;
    if (bl.group[b] != Group::specimen) continue;
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c) {
      const Point p{bl.x[b] + bl.corner[c].x, bl.y[b] + bl.corner[c].y};
      x0 = std::min(x0, p.x);
      x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y);
      y1 = std::max(y1, p.y);
    }
  }
  width_ = x1 - x0;
  height_ = y1 - y0;
  const double tol = 1e-9 * std::max(width_, height_);
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    if (bl.group[b] != Group::specimen) continue;
    bool left = false, right = false;
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c) {
      const std::uint32_t n = bl.next_corner(b, c);
      const double xa = bl.x[b] + bl.corner[c].x, xb = bl.x[b] + bl.corner[n].x;
      const bool on_left = std::abs(xa - x0) < tol && std::abs(xb - x0) < tol;
      const bool on_right = std::abs(xa - x1) < tol && std::abs(xb - x1) < tol;
      if (on_left || on_right) edges_.push_back({b, c});
      left |= on_left;
      right |= on_right;
    }
    const bool middle = std::abs(bl.y[b] - (y0 + 0.5 * height_)) < height_ / 6.0;
    if (middle && left) left_.push_back(b);
    if (middle && right) right_.push_back(b);
  }
}

namespace {

// Clears the lateral edges' loads, then adds each edge's force: `force(p0, p1)` N per m for the
// counter-clockwise edge p0 -> p1, at its midpoint (half to each end gridpoint on a zoned block).
template <class Force>
void apply_traction(model::Model& model, const std::vector<BoundaryEdge>& edges, Force force) {
  auto& bl = model.blocks;
  auto& z = model.zoning;
  for (const BoundaryEdge& e : edges) {
    bl.fx[e.block] = bl.fy[e.block] = bl.moment[e.block] = 0.0;
    if (bl.deformable[e.block]) {
      for (const auto g : {z.corner_gp[e.corner], z.corner_gp[bl.next_corner(e.block, e.corner)]})
        z.fx[static_cast<std::size_t>(g)] = z.fy[static_cast<std::size_t>(g)] = 0.0;
    }
  }
  for (const BoundaryEdge& e : edges) {
    const std::uint32_t b = e.block;
    if (bl.deformable[b]) {
      const auto g0 = static_cast<std::size_t>(z.corner_gp[e.corner]);
      const auto g1 = static_cast<std::size_t>(z.corner_gp[bl.next_corner(b, e.corner)]);
      const Point f = 0.5 * force(Point{z.x[g0], z.y[g0]}, Point{z.x[g1], z.y[g1]});
      for (const std::size_t g : {g0, g1}) {
        z.fx[g] += f.x;
        z.fy[g] += f.y;
      }
      continue;
    }
    const Point p0 = bl.to_world(b, bl.corner[e.corner]);
    const Point p1 = bl.to_world(b, bl.corner[bl.next_corner(b, e.corner)]);
    const Point f = force(p0, p1);
    const Point mid = 0.5 * (p0 + p1);
    bl.fx[b] += f.x;
    bl.fy[b] += f.y;
    bl.moment[b] += (mid.x - bl.x[b]) * f.y - (mid.y - bl.y[b]) * f.x;
  }
}

}  // namespace

void SpecimenBoundary::apply_confinement(model::Model& model, double sigma3) const {
  // f = -sigma3 n L with n L = (dy, -dx) for a counter-clockwise edge.
  apply_traction(model, edges_, [&](Point p0, Point p1) {
    return Point{-sigma3 * (p1.y - p0.y), sigma3 * (p1.x - p0.x)};
  });
}

void SpecimenBoundary::apply_stress(model::Model& model, const InSituStress& field) const {
  // f = -s.(n L) with the field at the edge's midpoint (compression positive).
  apply_traction(model, edges_, [&](Point p0, Point p1) {
    const StressTensor s = field.at(0.5 * (p0.y + p1.y));
    const Point nl{p1.y - p0.y, p0.x - p1.x};
    return Point{-(s.xx * nl.x + s.xy * nl.y), -(s.xy * nl.x + s.yy * nl.y)};
  });
}

void SpecimenBoundary::set_platen_velocity(model::Model& model, double v, bool both) const {
  auto& bl = model.blocks;
  const double v_bottom = both ? 0.5 * v : 0.0;
  if (top_ >= 0) bl.vy[static_cast<std::size_t>(top_)] = -(v - v_bottom);
  if (bottom_ >= 0) bl.vy[static_cast<std::size_t>(bottom_)] = v_bottom;
}

}  // namespace vorodec::loading
