// R1: a circular hole in an elastic plane-strain domain under far-field stresses (Kirsch).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "cases.hpp"
#include "scenes.hpp"
#include "vorodec/model/zoning.hpp"

namespace vorodec::verification {

namespace {

using model::Point;

// The verification target's rock and loading: a = 1 m, G 2.8 GPa, K 3.9 GPa; far-field
// p1 = 30 MPa vertical and p2 = 15 MPa horizontal compression (tension positive below).
constexpr double a = 1.0, G = 2.8e9, K = 3.9e9, Sx = -15e6, Sy = -30e6, rho = 1.0;
constexpr double half = 5.0;  // m, half width of the square domain
const double E = 9 * K * G / (3 * K + G), nu = (3 * K - 2 * G) / (2 * (3 * K + G));

struct Polar {
  double rr, tt, rt;
};
// Kirsch's stresses at (r, theta) [Jaeger2007-style closed form, tension positive].
Polar kirsch(double r, double t) {
  const double m = 0.5 * (Sx + Sy), d = 0.5 * (Sx - Sy), q = a * a / (r * r);
  return {m * (1 - q) + d * (1 - 4 * q + 3 * q * q) * std::cos(2 * t),
          m * (1 + q) - d * (1 + 3 * q * q) * std::cos(2 * t),
          -d * (1 + 2 * q - 3 * q * q) * std::sin(2 * t)};
}
// The same in x, y: sxx, syy, sxy.
std::array<double, 3> kirsch_xy(Point p) {
  const double r = std::hypot(p.x, p.y), t = std::atan2(p.y, p.x);
  const Polar s = kirsch(r, t);
  const double c = std::cos(t), n = std::sin(t);
  return {s.rr * c * c + s.tt * n * n - 2 * s.rt * n * c,
          s.rr * n * n + s.tt * c * c + 2 * s.rt * n * c,
          (s.rr - s.tt) * n * c + s.rt * (c * c - n * n)};
}
// m, the hole's share of the radial displacement (the total less the far field's uniform strain).
double kirsch_ur(double r, double t) {
  return a * a / (4 * G * r) *
         ((Sx + Sy) + (Sx - Sy) * (4 * (1 - nu) - a * a / (r * r)) * std::cos(2 * t));
}

}  // namespace

std::vector<CaseResult> r1_kirsch(double h, bool dug) {
  const auto t0 = std::chrono::steady_clock::now();
  const model::ElasticMaterial mat{E, nu};
  model::Model m;
  m.rounding_length = 0.01 * h;
  // Four blocks around the hole, joined along rays at 22.5 deg + k 90 deg (away from the axes the
  // case reads, and from the square's corners, where two blocks would meet at 45 deg tips): each
  // the part of the square between two rays outside the hole, the arc cut at about h.
  const auto ray_end = [](double phi) {
    const Point d{std::cos(phi), std::sin(phi)};
    return (half / std::max(std::abs(d.x), std::abs(d.y))) * d;
  };
  const double deg = std::numbers::pi / 180;
  // A multiple of four segments per quarter, so that gridpoints lie where the axes meet the wall.
  const int arc = 4 * static_cast<int>(std::ceil(0.125 * std::numbers::pi * a / h));
  for (int q = 0; q < 4; ++q) {
    const double p0 = (-67.5 + 90.0 * q) * deg, p1 = p0 + 90.0 * deg, corner = p0 + 22.5 * deg;
    std::vector<Point> poly{ray_end(p0),
                            std::sqrt(2.0) * half * Point{std::cos(corner), std::sin(corner)},
                            ray_end(p1)};
    for (int k = arc; k >= 0; --k) {
      const double t = p0 + 0.5 * std::numbers::pi * k / arc;
      poly.push_back(a * Point{std::cos(t), std::sin(t)});
    }
    // Graded zoning: h at the wall growing in proportion to r, so a zone's share of the
    // stress error, about h |grad sigma| ~ h(r) p a^2 / r^3, falls off away from the hole.
    model::add_deformable_block(
        m, poly, rho, mat, [h](Point p) { return h * std::max(1.0, std::hypot(p.x, p.y) / a); },
        model::Group::specimen);
  }
  // Dug: the hole starts filled by a fifth block on the same wall points, joined like the rays.
  const auto plug = static_cast<std::uint32_t>(m.blocks.size());
  if (dug) {
    std::vector<Point> disc;
    for (int k = 0; k < 4 * arc; ++k) {
      const double t = -67.5 * deg + 0.5 * std::numbers::pi * k / arc;
      disc.push_back(a * Point{std::cos(t), std::sin(t)});
    }
    model::add_deformable_block(m, disc, rho, mat, h, model::Group::specimen);
  }
  auto& z = m.zoning;
  // Kirsch's tractions on the outer boundary, so that the finite square carries the infinite
  // plate's field: each boundary zone edge's traction at its midpoint, half to each end. They
  // follow the edges as the body deforms (dead loads of unequal size would turn a free body).
  struct Edge {
    std::size_t g0, g1;
    std::array<double, 3> s;  // Kirsch's sxx, syy, sxy at the midpoint (the far field's before a
                              // dug hole is dug)
    double sign;              // (dy, -dx) times this points outwards
  };
  std::vector<Edge> edges;
  const auto on_side = [&](std::size_t g) {
    return std::abs(std::abs(z.x0[g]) - half) < 1e-9 || std::abs(std::abs(z.y0[g]) - half) < 1e-9;
  };
  for (const auto& zone : z.zones)
    for (int k = 0; k < 3; ++k) {
      const std::size_t g0 = zone.gp[k], g1 = zone.gp[(k + 1) % 3];
      if (!on_side(g0) || !on_side(g1)) continue;
      const Point p{z.x0[g0], z.y0[g0]}, q{z.x0[g1], z.y0[g1]};
      const bool vertical = std::abs(p.x - q.x) < 1e-9 && std::abs(std::abs(p.x) - half) < 1e-9;
      const bool horizontal = std::abs(p.y - q.y) < 1e-9 && std::abs(std::abs(p.y) - half) < 1e-9;
      if (!vertical && !horizontal) continue;
      const Point mid = 0.5 * (p + q), n{q.y - p.y, p.x - q.x};
      edges.push_back({g0, g1, dug ? std::array<double, 3>{Sx, Sy, 0.0} : kirsch_xy(mid),
                       dot(n, mid) > 0 ? 1.0 : -1.0});
    }
  const auto load = [&] {
    for (const Edge& e : edges) z.fx[e.g0] = z.fy[e.g0] = z.fx[e.g1] = z.fy[e.g1] = 0;
    for (const Edge& e : edges) {
      const Point n = e.sign * Point{z.y[e.g1] - z.y[e.g0], z.x[e.g0] - z.x[e.g1]};  // |n| = length
      const Point t{e.s[0] * n.x + e.s[2] * n.y, e.s[2] * n.x + e.s[1] * n.y};
      for (const std::size_t g : {e.g0, e.g1}) {
        z.fx[g] += 0.5 * t.x;
        z.fy[g] += 0.5 * t.y;
      }
    }
  };
  load();
  // The joints on the rays: ten times as stiff as a zone row (docs/theory.md §4.4).
  const double jk = 10 * (mat.lambda() + 2 * mat.shear_modulus()) / h;
  solver::SolverSettings s;
  s.local_damping = 0.8;
  // Density scaling to a quarter of a zone's P-wave transit (the static answer does not depend on
  // the masses).
  // Every gridpoint's mass then comes from the scaling (rho is far below what the step needs), so
  // the large zones away from the hole pass a wave in as few steps as the small ones.
  s.time_step = 0.25 * h / std::sqrt((mat.lambda() + 2 * mat.shear_modulus()) / 2500.0);
  auto solver = make_solver(m, "linear_elastic", params({{"jkn", jk}, {"jks", jk}}), s);
  double peak = 0;
  // The body floats: its rigid translation and rotation (no stiffness, so nothing damps them)
  // are taken out of the velocities after every step.
  const auto hold_rigid = [&] {
    double m0 = 0, px = 0, py = 0, l = 0, j = 0;
    for (std::size_t g = 0; g < z.gridpoints(); ++g) {
      m0 += z.mass[g];
      px += z.mass[g] * z.vx[g];
      py += z.mass[g] * z.vy[g];
      l += z.mass[g] * (z.x[g] * z.vy[g] - z.y[g] * z.vx[g]);
      j += z.mass[g] * (z.x[g] * z.x[g] + z.y[g] * z.y[g]);
    }
    const double w = l / j;
    for (std::size_t g = 0; g < z.gridpoints(); ++g) {
      z.vx[g] -= px / m0 - w * z.y[g];
      z.vy[g] -= py / m0 + w * z.x[g];
    }
  };
  const auto relax = [&] {
    peak = 0;
    for (long i = 0; i < 2000000; ++i) {
      load();
      solver->step();
      hold_rigid();
      const double ke = solver->kinetic_energy();
      peak = std::max(peak, ke);
      if (i > 2000 && ke < 1e-10 * peak) break;
    }
  };
  relax();
  // The hole's share of the displacement is measured from a reference: the far field's uniform
  // strain, or where a dug hole's wall stood before the plug went.
  const double l = mat.lambda(), det = (l + 2 * G) * (l + 2 * G) - l * l;
  const double exx = ((l + 2 * G) * Sx - l * Sy) / det, eyy = ((l + 2 * G) * Sy - l * Sx) / det;
  std::vector<double> ref_x(z.gridpoints()), ref_y(z.gridpoints());
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    ref_x[g] = dug ? z.x[g] : z.x0[g] + exx * z.x0[g];
    ref_y[g] = dug ? z.y[g] : z.y0[g] + eyy * z.y0[g];
  }
  if (dug) {  // the plug goes; the boundary now carries the holed plate's field
    const std::uint32_t removed[] = {plug};
    solver->remove_blocks(removed);
    for (Edge& e : edges) {
      const Point mid = 0.5 * (Point{z.x0[e.g0], z.y0[e.g0]} + Point{z.x0[e.g1], z.y0[e.g1]});
      e.s = kirsch_xy(mid);
    }
    relax();
  }
  // Zone stresses along the axes beyond 1.2 a (zones whose centroid lies within h / 2 of an
  // axis), against Kirsch at the centroid; and the hole's radial displacement where the axes
  // meet the wall.
  const double p1 = std::abs(Sy);
  double worst_r = 0, worst_t = 0;
  for (std::size_t i = 0; i < z.zones.size(); ++i) {
    if (m.blocks.group[z.zone_block[i]] != model::Group::specimen) continue;  // the plug
    Point c{0, 0};
    for (int k = 0; k < 3; ++k)
      c = c + (1.0 / 3) * Point{z.x0[z.zones[i].gp[k]], z.y0[z.zones[i].gp[k]]};
    const double r = std::hypot(c.x, c.y);
    if (r < 1.2 * a || (std::abs(c.y) > 0.5 * h && std::abs(c.x) > 0.5 * h)) continue;
    const double t = std::atan2(c.y, c.x), cs = std::cos(t), sn = std::sin(t);
    const model::ZoneStress st = z.stress(i);
    const double rr = st.xx * cs * cs + st.yy * sn * sn + 2 * st.xy * sn * cs;
    const double tt = st.xx * sn * sn + st.yy * cs * cs - 2 * st.xy * sn * cs;
    const Polar k = kirsch(r, t);
    worst_r = std::max(worst_r, std::abs(rr - k.rr) / p1);
    worst_t = std::max(worst_t, std::abs(tt - k.tt) / p1);
  }
  double worst_u = 0, ur_scale = 0;
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    if (m.blocks.group[z.block[g]] != model::Group::specimen) continue;  // the plug
    const double r = std::hypot(z.x0[g], z.y0[g]);
    if (std::abs(r - a) > 1e-6 * a) continue;
    const bool x_axis = std::abs(z.y0[g]) < 1e-9, y_axis = std::abs(z.x0[g]) < 1e-9;
    if (!x_axis && !y_axis) continue;
    const double t = std::atan2(z.y0[g], z.x0[g]);
    const double ux = z.x[g] - ref_x[g], uy = z.y[g] - ref_y[g];
    const double ur = (ux * z.x0[g] + uy * z.y0[g]) / r;
    ur_scale = std::max(ur_scale, std::abs(kirsch_ur(a, t)));
    worst_u = std::max(worst_u, std::abs(ur - kirsch_ur(a, t)));
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string settings = fmt::format(
      "zone size {:g} a at the wall, growing as r / a, {} zones, {} steps; 4 blocks joined on "
      "rays at 22.5 + k 90 deg{}",
      h / a, z.zones.size(), solver->steps(),
      dug ? "; the hole dug out of the loaded plate (a zoned plug removed by Solver::remove_blocks)"
          : "");
  const auto row = [&](std::string name, std::string ref, double error, double tolerance) {
    CaseResult r{dug ? "R5" : "R1",
                 (dug ? "dug out: " : "") + std::move(name),
                 std::move(ref),
                 0,
                 error,
                 error,
                 tolerance,
                 settings};
    r.seconds = seconds;
    return r;
  };
  return {row("Kirsch hole (a 1 m, p1 30, p2 15 MPa): sigma_r along both axes beyond 1.2 a",
              "Kirsch; largest |error| / p1", worst_r, 0.02),
          row("same: sigma_theta along both axes beyond 1.2 a", "Kirsch; largest |error| / p1",
              worst_t, 0.02),
          row(dug ? "same: the wall's radial displacement on both axes since the plug went"
                  : "same: hole's radial displacement at the wall on both axes (less the far "
                    "field's uniform strain)",
              "u_r = a^2 / (4 G r) [(Sx + Sy) + (Sx - Sy)(4 (1 - nu) - a^2 / r^2) cos 2 theta]; "
              "largest |error| / largest |u_r|",
              ur_scale > 0 ? worst_u / ur_scale : 1.0, 0.02)};
}

}  // namespace vorodec::verification
