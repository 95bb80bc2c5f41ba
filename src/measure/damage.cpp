#include "vorodec/measure/damage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::measure {

namespace {

bool is_failed(model::ContactState s) {
  return s == model::ContactState::tensile_failed || s == model::ContactState::shear_failed;
}

// Shoelace area of a counter-clockwise polygon.
double polygon_area(std::span<const Point> p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

// Block b's outline in the initial configuration (built with theta = 0 about x0, y0).
std::vector<Point> initial_polygon(const model::Blocks& bl, std::uint32_t b) {
  std::vector<Point> p;
  for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c)
    p.push_back(Point{bl.x0[b], bl.y0[b]} + bl.corner[c]);
  return p;
}

// Sutherland-Hodgman: the part of a convex or concave polygon inside the half plane
// sign * (coordinate axis of p) <= sign * bound.
std::vector<Point> clip(const std::vector<Point>& poly, bool y_axis, double sign, double bound) {
  std::vector<Point> out;
  const auto inside = [&](Point p) { return sign * ((y_axis ? p.y : p.x) - bound) <= 0.0; };
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point p = poly[i], q = poly[(i + 1) % poly.size()];
    const bool pin = inside(p), qin = inside(q);
    if (pin) out.push_back(p);
    if (pin != qin) {
      const double pv = y_axis ? p.y : p.x, qv = y_axis ? q.y : q.x;
      const double t = (bound - pv) / (qv - pv);
      out.push_back(p + t * (q - p));
    }
  }
  return out;
}

double area_in_box(const std::vector<Point>& poly, Point lo, Point hi) {
  std::vector<Point> p = clip(poly, false, -1.0, lo.x);
  p = clip(p, false, 1.0, hi.x);
  p = clip(p, true, -1.0, lo.y);
  p = clip(p, true, 1.0, hi.y);
  return p.size() >= 3 ? polygon_area(p) : 0.0;
}

struct GridIndex {
  Point origin;
  double cell;
  std::size_t nx, ny;
  std::size_t axis(double v, double o, std::size_t n) const {
    const double f = std::floor((v - o) / cell);
    if (!(f > 0.0)) return 0;
    return std::min(static_cast<std::size_t>(f), n - 1);
  }
  std::size_t of(Point p) const { return axis(p.x, origin.x, nx) + nx * axis(p.y, origin.y, ny); }
};

}  // namespace

double crack_orientation_deg(const laws::CrackEvent& e) {
  // The joint line runs along the contact tangent (-ny, nx).
  double ang = std::atan2(e.nx, -e.ny) * 180.0 / M_PI;
  if (ang < 0.0) ang += 180.0;
  if (ang >= 180.0) ang -= 180.0;
  return ang;
}

std::size_t rose_bin(double orientation_deg) {
  const double f = std::floor(orientation_deg / 10.0);
  if (!(f > 0.0)) return 0;
  return std::min(static_cast<std::size_t>(f), kRoseBins - 1);
}

DamageBaseline damage_baseline(const model::Model& m) {
  const model::Blocks& bl = m.blocks;
  DamageBaseline base;
  base.bonds_per_block.assign(bl.size(), 0);
  for (const model::Contact& c : m.contacts) {
    if (!c.bonded) continue;
    base.bonds.push_back({c.id, c.a, c.b, c.corner, c.edge, c.length});
    ++base.bonds_per_block[static_cast<std::size_t>(c.a)];
    ++base.bonds_per_block[static_cast<std::size_t>(c.b)];
  }
  std::sort(base.bonds.begin(), base.bonds.end(),
            [](const auto& x, const auto& y) { return x.id < y.id; });
  if (!base.bonds.empty()) base.bond_of_id.assign(base.bonds.back().id + 1, kNoBond);
  for (std::size_t i = 0; i < base.bonds.size(); ++i)
    base.bond_of_id[base.bonds[i].id] = static_cast<std::uint32_t>(i);
  constexpr double inf = std::numeric_limits<double>::infinity();
  base.lo = {inf, inf};
  base.hi = {-inf, -inf};
  std::size_t n = 0;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    if (bl.group[b] != model::Group::specimen) continue;
    const auto poly = initial_polygon(bl, b);
    base.specimen_area += polygon_area(poly);
    for (Point p : poly) {
      base.lo = {std::min(base.lo.x, p.x), std::min(base.lo.y, p.y)};
      base.hi = {std::max(base.hi.x, p.x), std::max(base.hi.y, p.y)};
    }
    ++n;
  }
  if (n == 0) base.lo = base.hi = {};
  base.mean_block_size = n ? std::sqrt(base.specimen_area / static_cast<double>(n)) : 0.0;
  return base;
}

std::vector<CrackOpening> crack_openings(const model::Model& m, const DamageBaseline& base) {
  // Present contacts by id; ids of later (unbonded) contacts never match an initial bond.
  std::vector<const model::Contact*> present(base.bonds.size(), nullptr);
  for (const model::Contact& c : m.contacts)
    if (c.id < base.bond_of_id.size() && base.bond_of_id[c.id] != kNoBond)
      present[base.bond_of_id[c.id]] = &c;
  std::vector<CrackOpening> out;
  for (std::size_t i = 0; i < base.bonds.size(); ++i) {
    const model::Contact* c = present[i];
    if (c && !is_failed(c->state)) continue;  // intact bonds are never deleted
    model::Contact probe;
    if (c) {
      probe = *c;
    } else {
      const auto& bond = base.bonds[i];
      probe.a = bond.a;
      probe.b = bond.b;
      probe.corner = bond.corner;
      probe.edge = bond.edge;
      probe.length = bond.length;
    }
    const model::ContactFrame f = model::contact_frame(m.blocks, probe);
    out.push_back({f.point, std::max(c ? c->gap : f.gap, 0.0), probe.length});
  }
  return out;
}

DamageState measure_damage(const model::Model& m, std::span<const laws::CrackEvent> cracks,
                           const DamageBaseline& base) {
  DamageState s;
  double length = 0.0, length_t = 0.0, length_s = 0.0;
  for (const laws::CrackEvent& e : cracks) {
    const bool tensile = e.type == laws::ContactEvent::tensile_failure;
    const std::size_t bin = rose_bin(crack_orientation_deg(e));
    ++(tensile ? s.cracks_tensile : s.cracks_shear);
    length += e.length;
    (tensile ? length_t : length_s) += e.length;
    s.rose[bin] += e.length;
    (tensile ? s.rose_tensile : s.rose_shear)[bin] += e.length;
  }
  s.cracks = cracks.size();
  s.failure_rate = base.bonds.empty()
                       ? 0.0
                       : static_cast<double>(s.cracks) / static_cast<double>(base.bonds.size());
  for (const CrackOpening& o : crack_openings(m, base)) s.crack_area += o.aperture * o.length;
  const double area = base.specimen_area;
  if (area > 0.0) {
    s.damage_density = s.crack_area / (s.crack_area + area);
    s.p21 = length / area;
    s.p21_tensile = length_t / area;
    s.p21_shear = length_s / area;
    for (std::size_t k = 0; k < kRoseBins; ++k) {
      s.rose[k] /= area;
      s.rose_tensile[k] /= area;
      s.rose_shear[k] /= area;
    }
  }
  return s;
}

std::vector<double> block_failed_fraction(std::span<const laws::CrackEvent> cracks,
                                          const DamageBaseline& base) {
  std::vector<double> f(base.bonds_per_block.size(), 0.0);
  for (const laws::CrackEvent& e : cracks)
    for (const std::int32_t b : {e.a, e.b}) f[static_cast<std::size_t>(b)] += 1.0;
  for (std::size_t b = 0; b < f.size(); ++b)
    f[b] = base.bonds_per_block[b] ? f[b] / static_cast<double>(base.bonds_per_block[b]) : 0.0;
  return f;
}

DamageGrid damage_grid(const model::Model& m, std::span<const laws::CrackEvent> cracks,
                       const DamageBaseline& base, double cell) {
  if (!(cell > 0.0)) throw std::invalid_argument("damage_grid: cell size must be positive");
  DamageGrid g;
  g.origin = base.lo;
  g.cell = cell;
  const auto cells = [&](double span) {
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(span / cell - 1e-9)));
  };
  g.nx = cells(base.hi.x - base.lo.x);
  g.ny = cells(base.hi.y - base.lo.y);
  const std::size_t n = g.nx * g.ny;
  for (auto* v : {&g.specimen_area, &g.crack_length, &g.crack_area, &g.p21, &g.damage_density})
    v->assign(n, 0.0);
  const GridIndex index{g.origin, cell, g.nx, g.ny};

  const model::Blocks& bl = m.blocks;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    if (bl.group[b] != model::Group::specimen) continue;
    const auto poly = initial_polygon(bl, b);
    Point lo = poly[0], hi = poly[0];
    for (Point p : poly) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const std::size_t i0 = index.axis(lo.x, g.origin.x, g.nx),
                      i1 = index.axis(hi.x, g.origin.x, g.nx);
    const std::size_t j0 = index.axis(lo.y, g.origin.y, g.ny),
                      j1 = index.axis(hi.y, g.origin.y, g.ny);
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) {
        const Point c0{g.origin.x + cell * static_cast<double>(i),
                       g.origin.y + cell * static_cast<double>(j)};
        g.specimen_area[i + g.nx * j] += area_in_box(poly, c0, c0 + Point{cell, cell});
      }
  }
  for (const laws::CrackEvent& e : cracks) g.crack_length[index.of({e.x, e.y})] += e.length;
  for (const CrackOpening& o : crack_openings(m, base))
    g.crack_area[index.of(o.point)] += o.aperture * o.length;
  for (std::size_t k = 0; k < n; ++k) {
    const double a = g.specimen_area[k];
    if (a <= 0.0) continue;
    g.p21[k] = g.crack_length[k] / a;
    g.damage_density[k] = g.crack_area[k] / (g.crack_area[k] + a);
  }
  return g;
}

}  // namespace vorodec::measure
