#include "vorodec/measure/joint_displacement.hpp"

#include <algorithm>
#include <cmath>

#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::measure {

using model::Point;

BlockPlacement placement_of(const model::Blocks& bl) {
  return {bl.x, bl.y, bl.theta};
}

std::vector<double> joint_displacements(const model::Model& m, const BlockPlacement& at,
                                        int first_law, std::size_t sets) {
  std::vector<double> most(2 * sets, 0.0);
  if (first_law < 0 || at.x.empty()) return most;
  const auto& bl = m.blocks;
  // Block b's material point now at p stood at c0 + R(theta0 - theta) (p - c).
  const auto was_at = [&](std::size_t b, Point p) {
    const double d = at.theta[b] - bl.theta[b], c = std::cos(d), s = std::sin(d);
    const Point r = p - Point{bl.x[b], bl.y[b]};
    return Point{at.x[b] + c * r.x - s * r.y, at.y[b] + s * r.x + c * r.y};
  };
  for (model::Contact k : m.contacts) {
    const int set = k.law - first_law;
    if (set < 0 || static_cast<std::size_t>(set) >= sets) continue;
    const model::ContactFrame f = model::contact_frame(bl, k);  // on a copy: k.edge may move
    // u_a - u_b: the corner's block a away from the edge's block b along n opens the joint.
    const Point d = was_at(static_cast<std::size_t>(k.b), f.point) -
                    was_at(static_cast<std::size_t>(k.a), f.point);
    double* s = &most[2 * static_cast<std::size_t>(set)];
    s[0] = std::max(s[0], std::abs(cross(f.n, d)));
    s[1] = std::max(s[1], dot(f.n, d));
  }
  return most;
}

}  // namespace vorodec::measure
