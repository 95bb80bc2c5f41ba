#include "implicit_start.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "vorodec/solver/elastic_response.hpp"

namespace vorodec::app {

namespace {

// Stage time at which the platen has moved `d` m: the velocity ramps linearly from 0 to v over
// `ramp` s, then stays at v.
double program_time(double d, double v, double ramp) {
  if (ramp <= 0.0) return d / v;
  return d >= 0.5 * v * ramp ? d / v + 0.5 * ramp : std::sqrt(2.0 * d * ramp / v);
}

}  // namespace

ImplicitStart implicit_start(model::Model& model, solver::Solver& solver,
                             const loading::SpecimenBoundary& boundary,
                             const loading::Stage& stage) {
  auto& bl = model.blocks;
  const std::size_t nb = bl.size();
  const auto top = static_cast<std::size_t>(boundary.top_platen());
  const auto bottom = static_cast<std::size_t>(boundary.bottom_platen());
  // Unit case: the top platen 1 m down (compression), the bottom one held.
  std::vector<std::array<double, 3>> unit(nb, {0.0, 0.0, 0.0});
  unit[top] = {0.0, -1.0, 0.0};
  const double fraction = stage.implicit_start_fraction;
  const int increments = stage.implicit_start_increments;
  ImplicitStart s;
  solver::ElasticResponse r;
  double done = 0.0, total = 0.0, time = 0.0;
  const double v = stage.platen_velocity;
  for (int k = 0; k < increments; ++k) {
    model::refresh_world(model);
    r = solver::elastic_response(model, solver.laws(), unit);
    s.passes += r.passes;
    s.solve_seconds += r.factorise_seconds;
    // Axial stress per metre of platen displacement, as measure_specimen takes it.
    const double stress_per_m =
        (r.force[top][1] - r.force[bottom][1]) / (2.0 * boundary.width() * model.thickness);
    if (k == 0) {
      s.dofs = r.dofs;
      s.active_contacts = r.active_contacts;
      s.reach = r.reach;
      s.modulus = stress_per_m * boundary.height();
      if (r.limiting_contact < model.contacts.size()) {
        const model::Contact& c = model.contacts[r.limiting_contact];
        s.limit = fmt::format("{}: blocks {} and {}",
                              r.limit_is_closing ? "an open contact closes"
                                                 : "first contact out of its elastic regime",
                              c.a, c.b);
      }
      total = fraction * r.reach;
      // The jump stops short of the stage's own end, so the stage still ends by its steps.
      const loading::StageEnd& end = stage.end;
      if (!std::isnan(end.axial_strain) && end.axial_strain > 0.0 &&
          fraction * end.axial_strain * boundary.height() < total) {
        total = fraction * end.axial_strain * boundary.height();
        s.limit = "end_axial_strain";
      }
      if (!std::isnan(end.axial_stress) && end.axial_stress > 0.0 && stress_per_m > 0.0 &&
          fraction * end.axial_stress / stress_per_m < total) {
        total = fraction * end.axial_stress / stress_per_m;
        s.limit = "end_axial_stress";
      }
      if (!std::isfinite(total))
        throw solver::ElasticResponseError(
            "nothing limits the implicit elastic start: no contact ever leaves its elastic "
            "regime and the stage has no end_axial_strain or end_axial_stress");
    }
    // Equal parts of what is left, each within the elastic reach from where it starts.
    const double d = std::min((total - done) / (increments - k), fraction * r.reach);
    std::vector<double> dx(nb), dy(nb), dt(nb);
    for (std::size_t b = 0; b < nb; ++b) {
      dx[b] = d * r.ux[b];
      dy[b] = d * r.uy[b];
      dt[b] = d * r.utheta[b];
    }
    const double t = program_time(done + d, v, stage.ramp_time);
    solver.displace(dx, dy, dt, t - time);
    done += d;
    time = t;
    s.stress += stress_per_m * d;
  }
  s.displacement = done;
  s.time = time;
  // The blocks go on moving as the linear response does at the platen's speed: no start-up wave.
  const double speed =
      stage.ramp_time > 0.0 && time < stage.ramp_time ? v * time / stage.ramp_time : v;
  for (std::size_t b = 0; b < nb; ++b) {
    if (bl.prescribed[b]) continue;
    bl.vx[b] = speed * r.ux[b];
    bl.vy[b] = speed * r.uy[b];
    bl.omega[b] = speed * r.utheta[b];
  }
  return s;
}

}  // namespace vorodec::app
