#include "vorodec/model/build.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vorodec/model/polygon.hpp"

namespace vorodec::model {

namespace {

// Arc of a corner rounded at distance d along both edges; the radius is capped so that nearly
// straight corners (interior angle near 180 degrees) do not get centres far inside the block.
void round_corner(Point prev, Point c, Point next, double d, Point& centre, double& radius) {
  Point u = prev - c, w = next - c;
  u = (1.0 / std::sqrt(dot(u, u))) * u;
  w = (1.0 / std::sqrt(dot(w, w))) * w;
  const double half = 0.5 * std::acos(std::clamp(dot(u, w), -1.0, 1.0));  // beta / 2
  radius = std::min(d * std::tan(half), 4.0 * d);
  Point bis = u + w;
  const double bl = std::sqrt(dot(bis, bis));
  // A straight corner (a T-junction split of an edge) has no bisector but round-off: the inward
  // normal of a counter-clockwise polygon, left of the edge direction -u.
  bis = bl > 1e-9 ? (1.0 / bl) * bis : Point{u.y, -u.x};
  centre = c + (radius / std::sin(half)) * bis;
}

}  // namespace

void add_block(Model& model, std::span<const Point> polygon, double density, Group group) {
  Blocks& b = model.blocks;
  const MassProperties mp = mass_properties(polygon);
  b.x.push_back(mp.centroid.x);
  b.y.push_back(mp.centroid.y);
  b.theta.push_back(0.0);
  b.x0.push_back(mp.centroid.x);
  b.y0.push_back(mp.centroid.y);
  for (auto* v : {&b.vx, &b.vy, &b.omega, &b.fx, &b.fy, &b.moment}) v->push_back(0.0);
  const double m = density * mp.area * model.thickness;
  b.mass.push_back(m);
  b.gravity_mass.push_back(m);
  b.inertia.push_back(density * mp.polar_moment * model.thickness);
  b.true_inertia.push_back(b.inertia.back());
  b.group.push_back(group);
  b.prescribed.push_back(group == Group::top_platen || group == Group::bottom_platen ? 1 : 0);
  b.deformable.push_back(0);
  b.cos_t.push_back(1.0);
  b.sin_t.push_back(0.0);
  if (b.corner_begin.empty()) b.corner_begin.push_back(0);
  const std::size_t n = polygon.size();
  const auto first = static_cast<std::uint32_t>(b.corner.size());
  std::vector<Point> centres(n);
  std::vector<double> radii(n);
  for (std::size_t i = 0; i < n; ++i) {
    round_corner(polygon[(i + n - 1) % n], polygon[i], polygon[(i + 1) % n], model.rounding_length,
                 centres[i], radii[i]);
    b.corner.push_back(polygon[i] - mp.centroid);
    b.round_centre.push_back(centres[i] - mp.centroid);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const Point e = polygon[j] - polygon[i];
    const double inv = 1.0 / std::sqrt(dot(e, e));
    b.shape.push_back({radii[i], inv, dot(centres[i] - polygon[i], inv * e),
                       dot(centres[j] - polygon[i], inv * e), first + static_cast<std::uint32_t>(j),
                       first + static_cast<std::uint32_t>((i + n - 1) % n)});
  }
  b.corner_begin.push_back(static_cast<std::uint32_t>(b.corner.size()));
  b.world.resize(b.corner.size());
  b.kin.resize(b.size());
}

namespace {
// Blocks turn little, so their rotation is almost always below this. There the Taylor series of
// sin to x^13 and of cos to x^14 are exact to rounding (next terms < 1e-21) and, unlike libm's
// sincos (about 92 instructions a call here), vectorise.
constexpr double small_angle = 0.25;

inline void small_angle_cos_sin(double t, double& c, double& s) {
  constexpr double s3 = -1.0 / 6, s5 = 1.0 / 120, s7 = -1.0 / 5040, s9 = 1.0 / 362880,
                   s11 = -1.0 / 39916800, s13 = 1.0 / 6227020800;
  constexpr double c2 = -1.0 / 2, c4 = 1.0 / 24, c6 = -1.0 / 720, c8 = 1.0 / 40320,
                   c10 = -1.0 / 3628800, c12 = 1.0 / 479001600, c14 = -1.0 / 87178291200;
  const double t2 = t * t;
  s = t + t * t2 * (s3 + t2 * (s5 + t2 * (s7 + t2 * (s9 + t2 * (s11 + t2 * s13)))));
  c = 1.0 + t2 * (c2 + t2 * (c4 + t2 * (c6 + t2 * (c8 + t2 * (c10 + t2 * (c12 + t2 * c14))))));
}

// World positions of corners [k0, k1) of a block at `origin` turned by (c, s). Restrict
// parameters: the caller's pointers might overlap for all the compiler knows, and it would test
// that at run time before every block's few corners.
inline void place_corners(const Point* __restrict corner, const Point* __restrict centre,
                          CornerWorld* __restrict world, std::uint32_t k0, std::uint32_t k1,
                          Point origin, double c, double s) {
  for (std::uint32_t k = k0; k < k1; ++k) {
    const Point p = corner[k], q = centre[k];
    world[k] = {{origin.x + c * p.x - s * p.y, origin.y + s * p.x + c * p.y},
                {origin.x + c * q.x - s * q.y, origin.y + s * q.x + c * q.y}};
  }
}
}  // namespace

void Blocks::refresh_world(bool skip_deformable, std::span<const std::size_t> parts) {
  const auto n = static_cast<std::int64_t>(size());
  // Plain pointers: through vector members the compiler must reload every block value after each
  // store to world (a double store might alias them).
  const Point *local_corner = corner.data(), *local_centre = round_centre.data();
  CornerWorld* w = world.data();
  const double* t = theta.data();
  double *cs = cos_t.data(), *sn = sin_t.data();
  const std::uint8_t* zoned = deformable.data();
#pragma omp parallel
  {
    // Each thread its own blocks in both loops, so no barrier between them. The first vectorises
    // as it is.
    const auto [lo, hi] = block_part(parts, n);
    for (std::int64_t b = lo; b < hi; ++b) small_angle_cos_sin(t[b], cs[b], sn[b]);
    for (std::int64_t bi = lo; bi < hi; ++bi) {
      const auto b = static_cast<std::size_t>(bi);
      if (skip_deformable && zoned[b]) continue;
      if (std::abs(t[b]) > small_angle) {
        cs[b] = std::cos(t[b]);
        sn[b] = std::sin(t[b]);
      }
      const double xb = x[b], yb = y[b];
      place_corners(local_corner, local_centre, w, corner_begin[b], corner_begin[b + 1], {xb, yb},
                    cs[b], sn[b]);
      kin[b] = {xb, yb, vx[b], vy[b], omega[b]};
    }
  }
}

Model build_model(const geometry::Tessellation& tess, const BuildSettings& settings,
                  const std::optional<DeformableBuild>& deformable) {
  Model model;
  model.rounding_length = settings.rounding_length;
  std::vector<Point> poly;
  double xmin = std::numeric_limits<double>::max(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (std::size_t k = 0; k < tess.blocks.size(); ++k) {
    const auto& blk = tess.blocks[k];
    poly.clear();
    for (std::uint32_t v : blk) {
      poly.push_back(tess.vertices[v]);
      xmin = std::min(xmin, poly.back().x);
      xmax = std::max(xmax, poly.back().x);
      ymin = std::min(ymin, poly.back().y);
      ymax = std::max(ymax, poly.back().y);
    }
    const double density =
        settings.block_density.empty() ? settings.density : settings.block_density[k];
    if (deformable)
      add_deformable_block(
          model, poly, density,
          deformable->block_material.empty() ? deformable->material : deformable->block_material[k],
          deformable->zone_size, Group::specimen);
    else
      add_block(model, poly, density, Group::specimen);
  }
  if (settings.bars) {  // rectangles of the bars' width centred on the specimen's axis
    const BlockBars& br = *settings.bars;
    const double x0 = 0.5 * (xmin + xmax) - 0.5 * br.width, x1 = x0 + br.width, h = br.block_length;
    const auto row = [&](double y, Group g, double density) {
      const Point r[] = {{x0, y}, {x1, y}, {x1, y + h}, {x0, y + h}};
      add_block(model, r, density, g);
    };
    row(ymin - h, Group::bottom_platen, br.transmitted_density);
    row(ymax, Group::top_platen, br.incident_density);
    for (int k = 1; k < br.transmitted_blocks; ++k)
      row(ymin - (k + 1) * h, Group::transmitted_bar, br.transmitted_density);
    for (int k = 1; k < br.incident_blocks; ++k)
      row(ymax + k * h, Group::incident_bar, br.incident_density);
    for (std::size_t b = 0; b < model.blocks.size(); ++b)  // the platens are bar blocks: free
      model.blocks.prescribed[b] = 0;
    return model;
  }
  if (settings.platens) {
    // Platens overhang the specimen by half its width; their mass never enters (velocity
    // prescribed).
    const double w = xmax - xmin, t = 0.25 * w;
    const Point bottom[] = {{xmin - 0.5 * w, ymin - t},
                            {xmax + 0.5 * w, ymin - t},
                            {xmax + 0.5 * w, ymin},
                            {xmin - 0.5 * w, ymin}};
    const Point top[] = {{xmin - 0.5 * w, ymax},
                         {xmax + 0.5 * w, ymax},
                         {xmax + 0.5 * w, ymax + t},
                         {xmin - 0.5 * w, ymax + t}};
    add_block(model, bottom, settings.density, Group::bottom_platen);
    add_block(model, top, settings.density, Group::top_platen);
  }
  return model;
}

}  // namespace vorodec::model
