#include "vorodec/model/zoning.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "vorodec/geometry/zone_mesh.hpp"
#include "vorodec/model/build.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::model {

namespace {

// The deformable blocks' world corners, unit edge directions (kept in the shape's inverse lengths)
// and rounded arcs, from their gridpoints: the corners of all blocks at once, each loop over
// independent corners so that it vectorises (the square roots and divisions dominate).
void refresh_corners(Model& model) {
  Blocks& bl = model.blocks;
  Zoning& z = model.zoning;
  CornerArrays& ca = z.corners;
  const double d = model.rounding_length;
  const auto n = static_cast<std::int64_t>(ca.corner.size());
  const auto nb = static_cast<std::int64_t>(ca.block_begin.size()) - 1;
  const std::uint32_t *corner = ca.corner.data(), *gp = ca.gp.data();
  const std::uint32_t* begin = ca.block_begin.data();
  const double *x = z.x.data(), *y = z.y.data();
  double *px = ca.px.data(), *py = ca.py.data(), *tx = ca.tx.data(), *ty = ca.ty.data();
  double *inv = ca.inv.data(), *cx = ca.cx.data(), *cy = ca.cy.data(), *rad = ca.radius.data();
#pragma omp parallel if (n >= 4096)
  {
    // The edge from corner j to corner k (its next).
    const auto edge = [=](std::int64_t j, std::int64_t k) __attribute__((always_inline)) {
      const double ex = px[k] - px[j], ey = py[k] - py[j];
      inv[j] = 1.0 / std::sqrt(ex * ex + ey * ey);
      tx[j] = inv[j] * ex;
      ty[j] = inv[j] * ey;
    };
#pragma omp for simd schedule(simd : static)
    for (std::int64_t j = 0; j < n; ++j) {
      px[j] = x[gp[j]];
      py[j] = y[gp[j]];
    }
    // The next corner is the next in the list (read without a gather) but at a block's last
    // corner, which is then done again with its block's first.
#pragma omp for simd schedule(simd : static)
    for (std::int64_t j = 0; j < n - 1; ++j) edge(j, j + 1);
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < nb; ++k) edge(begin[k + 1] - 1, begin[k]);
    // Each corner's rounded arc (docs/theory.md §5.2: tangent to both edges, radius d tan(beta/2)
    // capped at 4d as in model/build.cpp) from the unit directions u (to the previous corner) and w
    // (to the next), without trigonometry (this runs for every boundary gridpoint every step):
    // tan(beta/2) = |u - w| / |u + w|, and the centre lies at R / sin(beta/2) along the inward
    // bisector, i.e. at R perp(w - u) / (1 - u.w) with 1 - u.w = |u - w|^2 / 2. Boundary gridpoints
    // along an edge form straight (180 degree) corners: there |u + w| is round-off, so the radius
    // takes the cap, where |u x w| / (1 + u.w) (both round-off) gave any radius down to 0 and put
    // the arc's centre on the edge, and detection then chose a neighbour edge by chance (issue 26:
    // a false gap, a crack at 0.2 % of the peak).
    const auto arc = [=](std::int64_t j, std::int64_t i) __attribute__((always_inline)) {
      const double ux = -1.0 * tx[i], uy = -1.0 * ty[i];  // i: the previous corner
      const double fx = tx[j] - ux, fy = ty[j] - uy, sx = ux + tx[j], sy = uy + ty[j];
      const double a = std::sqrt(fx * fx + fy * fy), b = std::sqrt(sx * sx + sy * sy);
      const double r = a >= 4.0 * b ? 4.0 * d : d * a / b;
      const double k = r / (0.5 * a * a);
      rad[j] = r;
      cx[j] = px[j] + k * -fy;
      cy[j] = py[j] + k * fx;
    };
      // The previous corner is the previous in the list but at a block's first corner, as above.
#pragma omp for simd schedule(simd : static)
    for (std::int64_t j = 1; j < n; ++j) arc(j, j - 1);
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < nb; ++k) arc(begin[k], begin[k + 1] - 1);
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < nb; ++k) {
      for (std::uint32_t j = begin[k]; j < begin[k + 1]; ++j) {
        const std::uint32_t after = j + 1 < begin[k + 1] ? j + 1 : begin[k];  // the next corner
        const std::uint32_t c = corner[j];
        const Point t{tx[j], ty[j]}, p{px[j], py[j]};
        const Point centre{cx[j], cy[j]}, centre_next{cx[after], cy[after]};
        bl.world[c] = {p, centre};
        CornerShape& s = bl.shape[c];
        s.inv_length = inv[j];
        s.radius = rad[j];
        s.s0 = dot(centre - p, t);
        s.s1 = dot(centre_next - p, t);
      }
    }
  }
}

}  // namespace

namespace {
void add_zoned_block(Model& model, const geometry::ZoneMesh& mesh, double density,
                     const ElasticMaterial& material, Group group);
}  // namespace

void add_deformable_block(Model& model, const std::vector<Point>& polygon, double density,
                          const ElasticMaterial& material, double zone_size, Group group) {
  add_zoned_block(model, geometry::mesh_polygon(polygon, zone_size), density, material, group);
}

void add_deformable_block(Model& model, const std::vector<Point>& polygon, double density,
                          const ElasticMaterial& material, const geometry::ZoneSize& zone_size,
                          Group group) {
  add_zoned_block(model, geometry::mesh_polygon(polygon, zone_size), density, material, group);
}

namespace {
void add_zoned_block(Model& model, const geometry::ZoneMesh& mesh, double density,
                     const ElasticMaterial& material, Group group) {
  std::vector<Point> outline;
  for (std::uint32_t g : mesh.boundary) outline.push_back(mesh.points[g]);
  add_block(model, outline, density, group);
  Blocks& bl = model.blocks;
  Zoning& z = model.zoning;
  const auto b = static_cast<std::uint32_t>(bl.size() - 1);
  bl.deformable.back() = 1;

  const auto base = static_cast<std::uint32_t>(z.gridpoints());
  for (const Point& p : mesh.points) {
    for (auto* v : {&z.vx, &z.vy, &z.mass, &z.gravity_mass, &z.fx, &z.fy, &z.cfx, &z.cfy})
      v->push_back(0.0);
    z.x.push_back(p.x);
    z.y.push_back(p.y);
    z.x0.push_back(p.x);
    z.y0.push_back(p.y);
    z.block.push_back(b);
    z.prescribed.push_back(0);
  }
  const double lambda = material.lambda(), shear = material.shear_modulus();
  for (const auto& t : mesh.zones) {
    Zone zone{};
    const Point p[3] = {mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]};
    zone.area = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
    for (int k = 0; k < 3; ++k) {
      const Point pb = p[(k + 1) % 3], pc = p[(k + 2) % 3];
      zone.gp[static_cast<std::size_t>(k)] = base + t[static_cast<std::size_t>(k)];
      zone.bx[static_cast<std::size_t>(k)] = (pb.y - pc.y) / (2.0 * zone.area);
      zone.by[static_cast<std::size_t>(k)] = (pc.x - pb.x) / (2.0 * zone.area);
    }
    zone.lambda = lambda;
    zone.shear = shear;
    // Lumped mass: a third of the zone's mass to each corner.
    for (std::uint32_t g : zone.gp) {
      z.mass[g] += density * zone.area * model.thickness / 3.0;
      z.gravity_mass[g] = z.mass[g];
    }
    z.zones.push_back(zone);
    ZoneArrays& za = z.arrays;
    for (std::size_t k = 0; k < 3; ++k) {
      za.gp[k].push_back(zone.gp[k]);
      za.bx[k].push_back(zone.bx[k]);
      za.by[k].push_back(zone.by[k]);
    }
    za.area.push_back(zone.area);
    za.lambda.push_back(zone.lambda);
    za.shear.push_back(zone.shear);
    z.zone_block.push_back(b);
  }
  z.corner_gp.resize(bl.corner.size(), -1);
  CornerArrays& ca = z.corners;
  const std::uint32_t c0 = bl.corner_begin[b], n = bl.corner_begin[b + 1] - c0;
  if (ca.block_begin.empty()) ca.block_begin.push_back(0);
  for (std::uint32_t c = c0; c < c0 + n; ++c) {
    z.corner_gp[c] = static_cast<std::int32_t>(base + mesh.boundary[c - c0]);
    ca.corner.push_back(c);
    ca.gp.push_back(base + mesh.boundary[c - c0]);
  }
  ca.block_begin.push_back(static_cast<std::uint32_t>(ca.corner.size()));
  for (auto* v : {&ca.px, &ca.py, &ca.tx, &ca.ty, &ca.inv, &ca.cx, &ca.cy, &ca.radius})
    v->resize(ca.corner.size(), 0.0);
  z.arrays.ux.resize(z.gridpoints(), 0.0);
  z.arrays.uy.resize(z.gridpoints(), 0.0);
  z.blocks.push_back(b);
  z.zone_begin.push_back(static_cast<std::uint32_t>(z.zones.size() - mesh.zones.size()));
  z.gp_begin.push_back(base);
  z.gp_end.push_back(static_cast<std::uint32_t>(z.gridpoints()));
  refresh_deformable(model);
}
}  // namespace

void refresh_deformable(Model& model) {
  Blocks& bl = model.blocks;
  Zoning& z = model.zoning;
  const auto nd = static_cast<std::int64_t>(z.blocks.size());
  // Small models stay on one thread: a parallel region costs more than their work.
#pragma omp parallel for schedule(static) if (nd >= 64)
  for (std::int64_t k = 0; k < nd; ++k) {
    const std::uint32_t b = z.blocks[static_cast<std::size_t>(k)];
    double m = 0, mx = 0, my = 0, mu = 0, mv = 0;
    for (std::uint32_t g = z.gp_begin[static_cast<std::size_t>(k)];
         g < z.gp_end[static_cast<std::size_t>(k)]; ++g) {
      m += z.gravity_mass[g];
      mx += z.gravity_mass[g] * z.x[g];
      my += z.gravity_mass[g] * z.y[g];
      mu += z.gravity_mass[g] * z.vx[g];
      mv += z.gravity_mass[g] * z.vy[g];
    }
    bl.x[b] = mx / m;
    bl.y[b] = my / m;
    bl.vx[b] = mu / m;
    bl.vy[b] = mv / m;
    bl.kin[b] = {bl.x[b], bl.y[b], bl.vx[b], bl.vy[b], 0.0};
  }
  refresh_corners(model);
}

namespace {

// A zone in its own frame from its corners' displacements (u, v) and shape derivatives (bx, by):
// the force pass and the stress and strain asked for later both start here, so they agree to the
// last bit.
struct ZoneFrame {
  double cs, sn;              // R: the zone's turn
  double exx, eyy, exy;       // U - I (exy the tensor shear strain)
  double txx, tyy, txy, vol;  // Pa, the Biot stress D (U - I); vol = lambda (exx + eyy)
};
[[gnu::always_inline]] inline ZoneFrame zone_frame(double u0, double u1, double u2, double v0,
                                                   double v1, double v2, double bx0, double bx1,
                                                   double bx2, double by0, double by1, double by2,
                                                   double lambda, double shear) {
  // Deformation gradient F = [[a, b], [c, d]] = I + grad u over the initial zone.
  const double a = 1 + bx0 * u0 + bx1 * u1 + bx2 * u2;
  const double b = by0 * u0 + by1 * u1 + by2 * u2;
  const double c = bx0 * v0 + bx1 * v1 + bx2 * v2;
  const double d = 1 + by0 * v0 + by1 * v1 + by2 * v2;
  // Polar decomposition F = R U (2D: R turns by atan2(c - b, a + d)); the strain U - I is the
  // zone's own, so a rigid rotation of any size leaves it stress-free.
  const double inv_r = 1.0 / std::sqrt((a + d) * (a + d) + (c - b) * (c - b));
  ZoneFrame r;
  r.cs = (a + d) * inv_r;
  r.sn = (c - b) * inv_r;
  r.exx = r.cs * a + r.sn * c - 1.0;
  r.eyy = r.cs * d - r.sn * b - 1.0;
  r.exy = r.cs * b + r.sn * d;  // U is symmetric
  r.vol = lambda * (r.exx + r.eyy);
  r.txx = r.vol + 2.0 * shear * r.exx;
  r.tyy = r.vol + 2.0 * shear * r.eyy;
  r.txy = 2.0 * shear * r.exy;
  return r;
}

// Zone i's frame at the last force pass, with its in-situ stress.
ZoneFrame zone_frame(const Zoning& z, std::size_t i) {
  const ZoneArrays& q = z.arrays;
  const std::uint32_t g0 = q.gp[0][i], g1 = q.gp[1][i], g2 = q.gp[2][i];
  ZoneFrame r =
      zone_frame(q.ux[g0], q.ux[g1], q.ux[g2], q.uy[g0], q.uy[g1], q.uy[g2], q.bx[0][i], q.bx[1][i],
                 q.bx[2][i], q.by[0][i], q.by[1][i], q.by[2][i], q.lambda[i], q.shear[i]);
  if (!q.s0xx.empty()) {
    r.txx += q.s0xx[i];
    r.tyy += q.s0yy[i];
    r.txy += q.s0xy[i];
  }
  return r;
}

// Corner forces of a run of zones, kept small enough to stay in the first-level cache between
// the vector pass that computes them and the pass that adds them to the gridpoints.
constexpr std::int64_t kZoneChunk = 256;
struct ChunkForces {
  alignas(64) double fx0[kZoneChunk], fx1[kZoneChunk], fx2[kZoneChunk];
  alignas(64) double fy0[kZoneChunk], fy1[kZoneChunk], fy2[kZoneChunk];
};

// Zones [begin, end)'s corner forces (into f, from index 0) from the displacements q.ux, q.uy;
// `in_situ`: with the stress the zone started with (a separate instance, so a zoning without one
// pays nothing). Every zone on its own, the same arithmetic in the vector body and the remainder:
// the result does not depend on how the zones are split. The world-frame stress and strain are
// left to Zoning::stress and Zoning::strain, which outputs ask for every few hundred steps.
template <bool in_situ>
void stress_zones(Zoning& z, std::int64_t begin, std::int64_t end, ChunkForces& f) {
  ZoneArrays& q = z.arrays;
  const double *ux = q.ux.data(), *uy = q.uy.data();
  const std::uint32_t *g0 = q.gp[0].data(), *g1 = q.gp[1].data(), *g2 = q.gp[2].data();
  const double *bx0 = q.bx[0].data(), *bx1 = q.bx[1].data(), *bx2 = q.bx[2].data();
  const double *by0 = q.by[0].data(), *by1 = q.by[1].data(), *by2 = q.by[2].data();
  const double *area = q.area.data(), *lambda = q.lambda.data(), *shear = q.shear.data();
  double *fx0 = f.fx0, *fx1 = f.fx1, *fx2 = f.fx2, *fy0 = f.fy0, *fy1 = f.fy1, *fy2 = f.fy2;
  const double *s0xx = q.s0xx.data(), *s0yy = q.s0yy.data(), *s0xy = q.s0xy.data();
#pragma omp simd
  for (std::int64_t i = begin; i < end; ++i) {
    ZoneFrame r = zone_frame(ux[g0[i]], ux[g1[i]], ux[g2[i]], uy[g0[i]], uy[g1[i]], uy[g2[i]],
                             bx0[i], bx1[i], bx2[i], by0[i], by1[i], by2[i], lambda[i], shear[i]);
    if constexpr (in_situ) {
      r.txx += s0xx[i];
      r.tyy += s0yy[i];
      r.txy += s0xy[i];
    }
    // Nominal stress P = R T (T the Biot stress T0 + D (U - I), T0 the in-situ stress), the
    // derivative of the zone's energy A0 (T0:(U - I) + (U - I):D:(U - I) / 2) by F:
    // F^k = -A0 P . grad N_k.
    const double cs = r.cs, sn = r.sn;
    const double pxx = cs * r.txx - sn * r.txy, pxy = cs * r.txy - sn * r.tyy;
    const double pyx = sn * r.txx + cs * r.txy, pyy = sn * r.txy + cs * r.tyy;
    const double A = area[i];
    const std::int64_t k = i - begin;
    fx0[k] = -A * (pxx * bx0[i] + pxy * by0[i]);
    fy0[k] = -A * (pyx * bx0[i] + pyy * by0[i]);
    fx1[k] = -A * (pxx * bx1[i] + pxy * by1[i]);
    fy1[k] = -A * (pyx * bx1[i] + pyy * by1[i]);
    fx2[k] = -A * (pxx * bx2[i] + pxy * by2[i]);
    fy2[k] = -A * (pyx * bx2[i] + pyy * by2[i]);
  }
}

// Each thread takes whole blocks, about as many zones each: a block's zones touch only its own
// gridpoints, so a thread needs no other's displacements, and every gridpoint sums its zones in
// zone order whatever the number of threads.
template <bool in_situ>
void add_zone_forces(Zoning& z, std::vector<double>& out_fx, std::vector<double>& out_fy) {
  const auto nz = static_cast<std::int64_t>(z.zones.size());
  const auto nd = static_cast<std::int64_t>(z.blocks.size());
  ZoneArrays& q = z.arrays;
  const std::uint32_t *g0 = q.gp[0].data(), *g1 = q.gp[1].data(), *g2 = q.gp[2].data();
  const std::uint32_t* zone_begin = z.zone_begin.data();
  const double *x = z.x.data(), *y = z.y.data(), *x0 = z.x0.data(), *y0 = z.y0.data();
  double *ux = q.ux.data(), *uy = q.uy.data(), *ox = out_fx.data(), *oy = out_fy.data();
#pragma omp parallel if (nz >= 2048)
  {
    const std::int64_t parts = omp_get_num_threads(), t = omp_get_thread_num();
    // The first block at or after zone nz * part / parts.
    const auto first_block = [&](std::int64_t part) {
      return std::lower_bound(zone_begin, zone_begin + nd, nz * part / parts) - zone_begin;
    };
    const std::int64_t k0 = first_block(t), k1 = first_block(t + 1);
    if (k0 < k1) {
      const std::int64_t gb = z.gp_begin[static_cast<std::size_t>(k0)];
      const std::int64_t ge = z.gp_end[static_cast<std::size_t>(k1 - 1)];
#pragma omp simd
      for (std::int64_t g = gb; g < ge; ++g) {
        ux[g] = x[g] - x0[g];
        uy[g] = y[g] - y0[g];
        ox[g] = 0.0;
        oy[g] = 0.0;
      }
      const std::int64_t end = k1 < nd ? zone_begin[k1] : nz;
      ChunkForces f;
      for (std::int64_t s = zone_begin[k0]; s < end; s += kZoneChunk) {
        const std::int64_t e = std::min(s + kZoneChunk, end);
        stress_zones<in_situ>(z, s, e, f);
        for (std::int64_t i = s; i < e; ++i) {
          const std::int64_t k = i - s;
          ox[g0[i]] += f.fx0[k];
          oy[g0[i]] += f.fy0[k];
          ox[g1[i]] += f.fx1[k];
          oy[g1[i]] += f.fy1[k];
          ox[g2[i]] += f.fx2[k];
          oy[g2[i]] += f.fy2[k];
        }
      }
    }
  }
}

}  // namespace

void zone_forces(Zoning& z, std::vector<double>& out_fx, std::vector<double>& out_fy) {
  out_fx.resize(z.gridpoints());
  out_fy.resize(z.gridpoints());
  if (z.arrays.s0xx.empty())
    add_zone_forces<false>(z, out_fx, out_fy);
  else
    add_zone_forces<true>(z, out_fx, out_fy);
}

std::vector<double> zone_stiffness_bound(const Zoning& z) {
  std::vector<double> kx(z.gridpoints(), 0.0), ky(z.gridpoints(), 0.0);
  for (const Zone& q : z.zones) {
    const double p = q.lambda + 2.0 * q.shear, l = q.lambda, g = q.shear;
    for (std::size_t a = 0; a < 3; ++a) {
      double rx = 0, ry = 0;
      for (std::size_t b = 0; b < 3; ++b) {
        rx += std::abs(p * q.bx[a] * q.bx[b] + g * q.by[a] * q.by[b]) +
              std::abs(l * q.bx[a] * q.by[b] + g * q.by[a] * q.bx[b]);
        ry += std::abs(l * q.by[a] * q.bx[b] + g * q.bx[a] * q.by[b]) +
              std::abs(p * q.by[a] * q.by[b] + g * q.bx[a] * q.bx[b]);
      }
      kx[q.gp[a]] += q.area * rx;
      ky[q.gp[a]] += q.area * ry;
    }
  }
  for (std::size_t i = 0; i < kx.size(); ++i) kx[i] = std::max(kx[i], ky[i]);
  return kx;
}

namespace {
// Stress and strain turned into the world frame: R T R^T and R (U - I) R^T.
struct WorldState {
  ZoneStress stress;
  std::array<double, 3> strain;  // exx, eyy, gamma_xy (engineering)
};
WorldState world_state(const Zoning& z, std::size_t i) {
  const ZoneFrame r = zone_frame(z, i);
  const double c2 = r.cs * r.cs, s2 = r.sn * r.sn, cssn = r.cs * r.sn;
  WorldState w;
  w.stress.xx = c2 * r.txx - 2.0 * cssn * r.txy + s2 * r.tyy;
  w.stress.yy = s2 * r.txx + 2.0 * cssn * r.txy + c2 * r.tyy;
  w.stress.xy = cssn * (r.txx - r.tyy) + (c2 - s2) * r.txy;
  w.stress.zz = r.vol;
  w.strain = {c2 * r.exx - 2.0 * cssn * r.exy + s2 * r.eyy,
              s2 * r.exx + 2.0 * cssn * r.exy + c2 * r.eyy,
              2.0 * (cssn * (r.exx - r.eyy) + (c2 - s2) * r.exy)};
  return w;
}
}  // namespace

ZoneStress Zoning::stress(std::size_t zone) const {
  return world_state(*this, zone).stress;
}

std::array<double, 3> Zoning::strain(std::size_t zone) const {
  return world_state(*this, zone).strain;
}

double zone_strain_energy(const Zoning& z) {
  double e = 0.0;
  if (!z.arrays.s0xx.empty()) {  // from the stress alone: s.D^-1.s / 2 (it has no strain origin)
    for (std::size_t i = 0; i < z.zones.size(); ++i) {
      const double l = z.zones[i].lambda, g = z.zones[i].shear, p = l + 2.0 * g;
      const ZoneStress s = z.stress(i);
      const double sx = s.xx, sy = s.yy, t = s.xy;
      e += 0.5 * z.zones[i].area *
           ((p * (sx * sx + sy * sy) - 2.0 * l * sx * sy) / (4.0 * g * (l + g)) + t * t / g);
    }
    return e;
  }
  for (std::size_t i = 0; i < z.zones.size(); ++i) {
    const WorldState w = world_state(z, i);
    e += 0.5 * z.zones[i].area *
         (w.stress.xx * w.strain[0] + w.stress.yy * w.strain[1] + w.stress.xy * w.strain[2]);
  }
  return e;
}

ZoneStress mean_stress(const Model& model, Group group) {
  const Zoning& z = model.zoning;
  ZoneStress m;
  double area = 0.0;
  for (std::size_t i = 0; i < z.zones.size(); ++i) {
    if (model.blocks.group[z.zone_block[i]] != group) continue;
    const double a = z.zones[i].area;
    const ZoneStress s = z.stress(i);
    m.xx += a * s.xx;
    m.yy += a * s.yy;
    m.xy += a * s.xy;
    m.zz += a * s.zz;
    area += a;
  }
  if (area > 0) m = {m.xx / area, m.yy / area, m.xy / area, m.zz / area};
  return m;
}

}  // namespace vorodec::model
