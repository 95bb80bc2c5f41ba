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
  const model::BodyView view = model::body_view(bl, z);
  // A contact's 2x2 spring matrix and its coupling to the other side: row sums <= 3 max(Kn, Ks).
  for (std::size_t l = 0; l < laws_.size(); ++l) {
    for (std::size_t i = deformable_begin_[l]; i < law_begin_[l + 1]; ++i) {
      model::Contact c = model_.contacts[i];
      const double kc = 3.0 * laws_[l]->max_stiffness(i - law_begin_[l]);
      const model::ContactFrame f = model::contact_frame(bl, c);
      const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
      for (const model::BodyPoint& p :
           {model::corner_point(view, a, c.corner), model::edge_point(view, b, c.edge, f.point)}) {
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
  for (auto* w : {&work_boundary_, &work_body_, &work_damping_}) w->resize(z.gridpoints());
  double *x = z.x.data(), *y = z.y.data(), *vx = z.vx.data(), *vy = z.vy.data();
  const double *zfx = zfx_.data(), *zfy = zfy_.data(), *cfx = z.cfx.data(), *cfy = z.cfy.data();
  const double *bfx = z.fx.data(), *bfy = z.fy.data(), *mass = z.mass.data();
  const double* gravity_mass = z.gravity_mass.data();
  const std::uint8_t* prescribed = z.prescribed.data();
  double *wb = work_boundary_.data(), *wg = work_body_.data(), *wd = work_damping_.data();
  // Each gridpoint on its own (the vector body and the remainder do the same arithmetic); its work
  // is summed below, in gridpoint order, whatever the threads.
#pragma omp parallel for simd schedule(simd : static) if (ng >= 2048)
  for (std::int64_t i = 0; i < ng; ++i) {
    const double u0 = vx[i], v0 = vy[i];
    const double fx = zfx[i] + cfx[i] + bfx[i] + gravity_mass[i] * g.x;
    const double fy = zfy[i] + cfy[i] + bfy[i] + gravity_mass[i] * g.y;
    const double dfx = -alpha * std::abs(fx) * sign(u0);
    const double dfy = -alpha * std::abs(fy) * sign(v0);
    // Both branches computed, one kept: a branch would stop the loop from vectorising.
    const bool free = !prescribed[i];
    const double u_free = u0 + (fx + dfx) / mass[i] * dt, v_free = v0 + (fy + dfy) / mass[i] * dt;
    const double u = free ? u_free : u0, v = free ? v_free : v0;
    vx[i] = u;
    vy[i] = v;
    const double w_applied = (bfx[i] * u + bfy[i] * v) * dt;
    const double w_held = -(((zfx[i] + cfx[i]) * u + (zfy[i] + cfy[i]) * v) * dt);
    const double w_gravity = gravity_mass[i] * (g.x * u + g.y * v) * dt;
    const double w_damping =
        -((dfx * (u0 + u) + dfy * (v0 + v)) * 0.5 * dt);  // as integrate_blocks
    wb[i] = free ? w_applied : w_held;
    wg[i] = free ? w_gravity : 0.0;
    wd[i] = free ? w_damping : 0.0;
    x[i] += u * dt;
    y[i] += v * dt;
  }
  double w_boundary = 0, w_body = 0, w_damp = 0;
  for (std::size_t i = 0; i < z.gridpoints(); ++i) {
    w_boundary += wb[i];
    w_body += wg[i];
    w_damp += wd[i];
  }
  energy_.boundary_work += w_boundary;
  energy_.body_work += w_body;
  energy_.damping += w_damp;
}

double Solver::zone_strain_energy() const {
  return model::zone_strain_energy(model_.zoning);
}

}  // namespace vorodec::solver
