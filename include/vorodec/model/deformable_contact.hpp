#pragma once
// How a contact point moves on either body representation (docs/theory.md §4.4): rigidly with its
// block, or with the gridpoints of a deformable block (corner: its gridpoint; edge: its two end
// gridpoints weighted by the contact point's position along the edge).
#include <algorithm>

#include "vorodec/model/model.hpp"

namespace vorodec::model {

// g0 < 0: a rigid block. Otherwise gridpoint g0 with weight 1 - w1, and g1 (if >= 0) with w1.
struct BodyPoint {
  std::int32_t g0 = -1, g1 = -1;
  double w1 = 0.0;
};

inline BodyPoint corner_point(const Blocks& bl, const Zoning& z, std::size_t block,
                              std::uint32_t corner) {
  if (!bl.deformable[block]) return {};
  return {z.corner_gp[corner], -1, 0.0};
}

inline BodyPoint edge_point(const Blocks& bl, const Zoning& z, std::size_t block,
                            std::uint32_t edge, Point p) {
  if (!bl.deformable[block]) return {};
  const std::uint32_t e1 = bl.shape[edge].next;
  const Point v0 = bl.world[edge].corner, e = bl.world[e1].corner - v0;
  const double xi = std::clamp(dot(p - v0, e) / dot(e, e), 0.0, 1.0);
  return {z.corner_gp[edge], z.corner_gp[e1], xi};
}

inline Point velocity_at(const Blocks& bl, const Zoning& z, std::size_t block, const BodyPoint& bp,
                         Point p) {
  if (bp.g0 < 0) {
    const BlockKinematics& k = bl.kin[block];
    return {k.vx - k.omega * (p.y - k.y), k.vy + k.omega * (p.x - k.x)};
  }
  const auto g0 = static_cast<std::size_t>(bp.g0);
  if (bp.g1 < 0) return {z.vx[g0], z.vy[g0]};
  const auto g1 = static_cast<std::size_t>(bp.g1);
  return {(1.0 - bp.w1) * z.vx[g0] + bp.w1 * z.vx[g1], (1.0 - bp.w1) * z.vy[g0] + bp.w1 * z.vy[g1]};
}

}  // namespace vorodec::model
