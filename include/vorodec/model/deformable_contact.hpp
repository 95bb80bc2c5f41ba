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

// What these functions read of both representations, as plain pointers: behind a Blocks&, the
// compiler would reload them after every one-byte store (a contact's state), which may alias them.
struct BodyView {
  CornerView corners;
  const std::uint8_t* deformable;
  const BlockKinematics* kin;
  const std::int32_t* corner_gp;
  const double *vx, *vy;  // m/s, gridpoint velocities
};

inline BodyView body_view(const Blocks& bl, const Zoning& z) {
  return {bl.corners(),       bl.deformable.data(), bl.kin.data(),
          z.corner_gp.data(), z.vx.data(),          z.vy.data()};
}

inline BodyPoint corner_point(const BodyView& v, std::size_t block, std::uint32_t corner) {
  if (!v.deformable[block]) return {};
  return {v.corner_gp[corner], -1, 0.0};
}

inline BodyPoint edge_point(const BodyView& v, std::size_t block, std::uint32_t edge, Point p) {
  if (!v.deformable[block]) return {};
  const std::uint32_t e1 = v.corners.shape[edge].next;
  const Point v0 = v.corners.world[edge].corner, e = v.corners.world[e1].corner - v0;
  const double xi = std::clamp(dot(p - v0, e) / dot(e, e), 0.0, 1.0);
  return {v.corner_gp[edge], v.corner_gp[e1], xi};
}

inline Point velocity_at(const BodyView& v, std::size_t block, const BodyPoint& bp, Point p) {
  if (bp.g0 < 0) {
    const BlockKinematics& k = v.kin[block];
    return {k.vx - k.omega * (p.y - k.y), k.vy + k.omega * (p.x - k.x)};
  }
  const auto g0 = static_cast<std::size_t>(bp.g0);
  if (bp.g1 < 0) return {v.vx[g0], v.vy[g0]};
  const auto g1 = static_cast<std::size_t>(bp.g1);
  return {(1.0 - bp.w1) * v.vx[g0] + bp.w1 * v.vx[g1], (1.0 - bp.w1) * v.vy[g0] + bp.w1 * v.vy[g1]};
}

}  // namespace vorodec::model
