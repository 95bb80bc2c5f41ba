#include "vorodec/engine/in_situ_start.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::run {

namespace {

// m, the length of the boundary blocks a and b share along b's edge p0 -> p1 (unit tangent u,
// normal n): the overlap of the edge with a's corners on its line (0: they touch at a point).
double shared_length(const model::Blocks& bl, std::int32_t a, model::Point p0, model::Point p1,
                     model::Point u, model::Point n) {
  const double edge = dot(p1 - p0, u), tol = 1e-9 * edge;
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  int on_line = 0;
  const auto b = static_cast<std::size_t>(a);
  for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c) {
    const model::Point q = bl.world[c].corner - p0;
    if (std::abs(dot(q, n)) > tol) continue;
    lo = std::min(lo, dot(q, u));
    hi = std::max(hi, dot(q, u));
    ++on_line;
  }
  return on_line < 2 ? 0.0 : std::max(0.0, std::min(hi, edge) - std::max(lo, 0.0));
}

// Each zone starts with the field at its centroid (tension positive, as zones count it).
void preload_zones(model::Zoning& z, solver::Solver& solver, const loading::InSituStress& field) {
  auto& q = z.arrays;
  const std::size_t n = z.zones.size();
  for (auto* v : {&q.s0xx, &q.s0yy, &q.s0xy}) v->assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& gp = z.zones[i].gp;
    const double y = (z.y0[gp[0]] + z.y0[gp[1]] + z.y0[gp[2]]) / 3.0;
    const loading::StressTensor s = field.at(y);
    q.s0xx[i] = -s.xx;
    q.s0yy[i] = -s.yy;
    q.s0xy[i] = -s.xy;
  }
  solver.add_initial_energy(model::zone_strain_energy(z));
}

}  // namespace

// The traction s.n_e per unit length (n_e the shared edge's normal): every block starts in
// equilibrium under a uniform field, and under a field whose gradient balances gravity.
void preload_in_situ(model::Model& model, solver::Solver& solver,
                     const loading::InSituStress& field) {
  if (!model.zoning.empty()) preload_zones(model.zoning, solver, field);
  const model::Blocks& bl = model.blocks;
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::size_t>> pairs;
  std::vector<model::ContactFrame> frames;
  for (std::size_t i = 0; i < model.contacts.size(); ++i) {
    model::Contact c = model.contacts[i];  // a copy: the frame may move its edge
    frames.push_back(model::contact_frame(bl.corners(), c));
    pairs[{std::min(c.a, c.b), std::max(c.a, c.b)}].push_back(i);
  }
  for (const auto& [blocks, members] : pairs) {
    // The shared boundary: the second block's edges that the first lies along (a zoned block's
    // edge is several collinear ones), its normal that of the longest.
    double shared = 0, longest = 0;
    model::Point n{0, 0};  // from the second block towards the first
    const auto second = static_cast<std::size_t>(blocks.second);
    for (std::uint32_t e = bl.corner_begin[second]; e < bl.corner_begin[second + 1]; ++e) {
      const model::Point p0 = bl.world[e].corner, p1 = bl.world[bl.shape[e].next].corner;
      const model::Point u = (1.0 / std::sqrt(dot(p1 - p0, p1 - p0))) * (p1 - p0);
      const double length = shared_length(bl, blocks.first, p0, p1, u, {u.y, -u.x});
      shared += length;
      if (length > longest) {
        longest = length;
        n = {u.y, -u.x};
      }
    }
    if (shared == 0) continue;
    double lengths = 0;
    for (const std::size_t i : members) lengths += model.contacts[i].length;
    const double scale = shared / lengths;
    for (const std::size_t i : members) {
      const model::ContactFrame& f = frames[i];
      const loading::StressTensor s = field.at(f.point.y);
      // The force on the contact's block a: its normal n points from b to a.
      const double w =
          model.contacts[i].length * scale * (model.contacts[i].a == blocks.first ? 1.0 : -1.0);
      const model::Point force{w * (s.xx * n.x + s.xy * n.y), w * (s.xy * n.x + s.yy * n.y)};
      const model::Point t{-f.n.y, f.n.x};
      // On an end arc the shear force acts with the frame's gain (ContactFrame).
      if (!solver.preload(i, dot(force, f.n), dot(force, t) / f.gain))
        throw std::logic_error("in-situ stress: a contact's law cannot start loaded");
    }
  }
}

}  // namespace vorodec::run
