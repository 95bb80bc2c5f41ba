#pragma once
// Gap, normal and contact point between a rounded corner and a block edge with rounded ends
// (docs/theory.md §5.3). Used by the step kernel and by contact detection.
#include <cmath>
#include <limits>

#include "vorodec/model/model.hpp"

namespace vorodec::model {

struct ContactFrame {
  Point n;      // unit normal from the edge owner towards the corner owner
  double gap;   // m, negative = overlap
  Point point;  // contact point, middle of the gap
  int side;     // -1: against the edge's start corner, 0: straight part, +1: against its end corner
  // The conservative shear coordinate (README "Energy conservation"), a function of both blocks'
  // positions: the coordinate of the corner's arc centre `arm` along the edge, continued on an
  // end arc by rho psi, rho the radii's sum and psi the normal's angle from the edge's outward
  // normal, `ray` = (cos psi, sin psi). On the straight part `shear` is the coordinate and rho
  // 0; on an arc `shear` is its tangent point's (shear_coordinate() adds rho psi). The
  // coordinate's gradient with respect to the arm is gain * s, so the force n fn + gain s fs
  // applied at the arm to a (and minus it to b) derives from the springs' energy.
  Point arm;
  double shear;
  double gain;
  double rho;
  Point ray;
};

// The shear coordinate of frame f, m (an atan2 on an end arc: for a contact's first step and
// where its edge changes; the steps between follow the arc by turn()).
inline double shear_coordinate(const ContactFrame& f) {
  return f.rho == 0.0 ? f.shear : f.shear + f.rho * std::atan2(f.ray.y, f.ray.x);
}

// Angle (rad) from unit vector a to unit vector b: one step's turn, so the series of atan(x),
// x = tan of the angle, to x^7 (remainder below 1.2e-19 for |x| < 1e-2); atan2 beyond.
inline double turn(Point a, Point b) {
  const double c = dot(a, b), s = cross(a, b);
  if (!(c > 0.0 && std::abs(s) < 1e-2 * c)) return std::atan2(s, c);
  const double x = s / c, x2 = x * x;
  return x * (1.0 - x2 * (1.0 / 3.0 - x2 * (1.0 / 5.0 - x2 / 7.0)));
}

// Corner arc (cA, rA) against edge v0 -> v1 of length `len` whose end arcs are (c0, r0) and
// (c1, r1).
inline ContactFrame corner_edge_frame(Point cA, double rA, Point v0, Point v1, double len, Point c0,
                                      double r0, Point c1, double r1) {
  const Point e = v1 - v0;
  const double inv_len = 1.0 / len;
  const Point t = inv_len * e;
  const double s = dot(cA - v0, t);
  ContactFrame f;
  f.side = s < dot(c0 - v0, t) ? -1 : (s > dot(c1 - v0, t) ? 1 : 0);
  if (f.side == 0) {
    f.n = {t.y, -t.x};  // outward normal of a counter-clockwise polygon's edge
    f.gap = dot(cA - v0, f.n) - rA;
  } else {
    const Point cb = f.side < 0 ? c0 : c1;
    const Point d = cA - cb;
    const double dist = std::sqrt(dot(d, d));
    f.n = (1.0 / dist) * d;
    f.gap = dist - rA - (f.side < 0 ? r0 : r1);
  }
  f.point = cA - (rA + 0.5 * f.gap) * f.n;
  f.arm = cA;  // detection reads the gap and the point; the step's contact_frame gives the shear
  f.shear = std::numeric_limits<double>::quiet_NaN();
  f.gain = 1.0;
  f.rho = 0.0;
  f.ray = {1.0, 0.0};
  return f;
}

// Geometry of contact c from the world arrays (Blocks::refresh_world), walking to a neighbouring
// edge of b when the corner has moved past the arc at the end of its current edge (updates c.edge).
inline ContactFrame contact_frame(const CornerView& bl, Contact& c) {
  const Point cA = bl.world[c.corner].centre;
  const double rA = bl.shape[c.corner].radius;
  for (int walk = 0;; ++walk) {
    const std::uint32_t e0 = c.edge;
    const CornerShape& edge = bl.shape[e0];
    const std::uint32_t e1 = edge.next;
    const Point v0 = bl.world[e0].corner;
    const Point t = edge.inv_length * (bl.world[e1].corner - v0);
    const Point r = cA - v0;
    const double s = dot(r, t);
    ContactFrame f;
    if (s >= edge.s0 && s <= edge.s1) {  // the straight part: the common case
      f.side = 0;
      f.n = {t.y, -t.x};
      f.gap = dot(r, f.n) - rA;
      f.point = cA - (rA + 0.5 * f.gap) * f.n;
      f.arm = cA;
      f.shear = s;
      f.gain = 1.0;
      f.rho = 0.0;
      f.ray = {1.0, 0.0};
      return f;
    }
    f.side = s < edge.s0 ? -1 : 1;
    const std::uint32_t ec = f.side < 0 ? e0 : e1;
    const Point d = cA - bl.world[ec].centre;
    const double dist = std::sqrt(dot(d, d));
    f.n = (1.0 / dist) * d;
    f.gap = dist - rA - bl.shape[ec].radius;
    f.point = cA - (rA + 0.5 * f.gap) * f.n;
    // Continuous with the straight part: the tangent point's coordinate plus rho psi, psi the
    // normal's angle from the edge's outward normal and rho the radii's sum (a constant). An arc
    // belongs to both edges that meet at its corner, and detection may hand the contact from
    // one to the other: the gain rho / dist is the same on both, so the force does not jump
    // there (with rho sin(psi) it would, and the energy with it: measured).
    const Point ne{t.y, -t.x};
    const double rho = rA + bl.shape[ec].radius;
    f.arm = cA;
    f.shear = f.side < 0 ? edge.s0 : edge.s1;
    f.gain = rho / dist;
    f.rho = rho;
    f.ray = {dot(ne, f.n), cross(ne, f.n)};
    if (walk == 2) return f;
    // Past the arc onto the neighbouring edge? Then that edge is the contact's feature.
    if (f.side < 0) {
      const std::uint32_t ep = edge.prev;
      if (dot(d, v0 - bl.world[ep].corner) >= 0.0) return f;
      c.edge = ep;
    } else {
      if (dot(d, bl.world[bl.shape[e1].next].corner - bl.world[e1].corner) <= 0.0) return f;
      c.edge = e1;
    }
  }
}

inline ContactFrame contact_frame(const Blocks& bl, Contact& c) {
  return contact_frame(bl.corners(), c);
}

}  // namespace vorodec::model
