// The gridpoints of deformable blocks (docs/theory.md §9.2, 4): their critical time step and
// density scaling, and their integration with zone and contact forces.
#include <algorithm>
#include <cmath>
#include <limits>

#include "vorodec/model/contact_geometry.hpp"
#include "vorodec/model/deformable_contact.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::solver {

namespace {
double sign(double v) {
  return (v > 0.0) - (v < 0.0);
}
}  // namespace

double Solver::gridpoint_time_step() {
  auto& z = model_.zoning;
  const auto& bl = model_.blocks;
  std::vector<double> k = model::zone_stiffness_bound(z);
  // A contact's 2x2 spring matrix and its coupling to the other side: row sums <= 3 max(Kn, Ks).
  for (std::size_t l = 0; l < laws_.size(); ++l) {
    for (std::size_t i = deformable_begin_[l]; i < law_begin_[l + 1]; ++i) {
      model::Contact c = model_.contacts[i];
      const double kc = 3.0 * laws_[l]->max_stiffness(i - law_begin_[l]);
      const model::ContactFrame f = model::contact_frame(bl, c);
      const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
      for (const model::BodyPoint& p : {model::corner_point(bl, z, a, c.corner),
                                        model::edge_point(bl, z, b, c.edge, f.point)}) {
        if (p.g0 >= 0) k[static_cast<std::size_t>(p.g0)] += kc;
        if (p.g1 >= 0) k[static_cast<std::size_t>(p.g1)] += kc;
      }
    }
  }
  const double s = settings_.safety_factor, target = settings_.time_step;
  double dt = std::numeric_limits<double>::max();
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    if (z.prescribed[g] || k[g] == 0.0) continue;
    if (target > 0.0)  // density scaling (docs/theory.md §9.3)
      z.mass[g] = std::max(z.gravity_mass[g], k[g] * target * target / (4.0 * s * s));
    // Gershgorin: no eigenvalue of M^-1 K exceeds max k/m, so 2 sqrt(m/k) is stable.
    dt = std::min(dt, 2.0 * std::sqrt(z.mass[g] / k[g]));
  }
  return dt;
}

void Solver::integrate_gridpoints() {
  auto& z = model_.zoning;
  model::zone_forces(z, zfx_, zfy_);
  const auto ng = static_cast<std::int64_t>(z.gridpoints());
  const double alpha = settings_.local_damping, dt = dt_;
  const model::Point g = settings_.gravity;
  double w_boundary = 0, w_body = 0, w_damp = 0;
#pragma omp parallel for schedule(static) if (ng >= 2048) reduction(+ : w_boundary, w_body, w_damp)
  for (std::int64_t gi = 0; gi < ng; ++gi) {
    const auto i = static_cast<std::size_t>(gi);
    double u = z.vx[i], v = z.vy[i];
    if (z.prescribed[i]) {
      w_boundary -= ((zfx_[i] + z.cfx[i]) * u + (zfy_[i] + z.cfy[i]) * v) * dt;
    } else {
      const double fx = zfx_[i] + z.cfx[i] + z.fx[i] + z.gravity_mass[i] * g.x;
      const double fy = zfy_[i] + z.cfy[i] + z.fy[i] + z.gravity_mass[i] * g.y;
      const double dfx = -alpha * std::abs(fx) * sign(u);
      const double dfy = -alpha * std::abs(fy) * sign(v);
      const double u0 = u, v0 = v;
      u += (fx + dfx) / z.mass[i] * dt;
      v += (fy + dfy) / z.mass[i] * dt;
      z.vx[i] = u;
      z.vy[i] = v;
      w_damp -= (dfx * (u0 + u) + dfy * (v0 + v)) * 0.5 * dt;  // as integrate_blocks
      w_boundary += (z.fx[i] * u + z.fy[i] * v) * dt;
      w_body += z.gravity_mass[i] * (g.x * u + g.y * v) * dt;
    }
    z.x[i] += u * dt;
    z.y[i] += v * dt;
  }
  energy_.boundary_work += w_boundary;
  energy_.body_work += w_body;
  energy_.damping += w_damp;
}

double Solver::zone_strain_energy() const {
  return model::zone_strain_energy(model_.zoning);
}

}  // namespace vorodec::solver
