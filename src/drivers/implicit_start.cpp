#include "implicit_start.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "vorodec/io/json.hpp"
#include "vorodec/measure/specimen.hpp"
#include "vorodec/solver/elastic_response.hpp"

namespace vorodec::run {

namespace {

// Stage time at which the platen has moved `d` m: the velocity ramps linearly from 0 to v over
// `ramp` s, then stays at v.
double program_time(double d, double v, double ramp) {
  if (ramp <= 0.0) return d / v;
  return d >= 0.5 * v * ramp ? d / v + 0.5 * ramp : std::sqrt(2.0 * d * ramp / v);
}

// Platen displacement (m) the jump aims at: `reach` (already x the fraction), or short of the
// stage's end strain or of the platen displacement `to_end_stress` (m) that reaches its end stress,
// so that the stage still ends by its steps. `limit` names what decided.
double jump_target(double reach, const loading::Stage& stage, double height, double to_end_stress,
                   std::string& limit) {
  const double fraction = stage.implicit_start_fraction;
  const loading::StageEnd& end = stage.end;
  double total = reach;
  if (!std::isnan(end.axial_strain) && end.axial_strain > 0.0 &&
      fraction * end.axial_strain * height < total) {
    total = fraction * end.axial_strain * height;
    limit = "end_axial_strain";
  }
  if (!std::isnan(end.axial_stress) && end.axial_stress > 0.0 && std::isfinite(to_end_stress) &&
      to_end_stress > 0.0 && fraction * to_end_stress < total) {
    total = fraction * to_end_stress;
    limit = "end_axial_stress";
  }
  return total;
}

// Fraction of a part (platen d m, load `part`) that stops where the first open contact closes:
// it enters K at the next solve.
double closing_scale(const model::Model& model, const solver::ElasticResponse& r, double d,
                     double part) {
  double scale = 1.0;
  for (std::size_t i = 0; i < model.contacts.size(); ++i) {
    const double gap = model.contacts[i].gap, dn = part * r.load.dn[i] + d * r.unit.dn[i];
    if (!r.active[i] && gap > r.touch && dn < 0.0 && gap + dn < r.touch)
      scale = std::min(scale, (gap - 0.5 * r.touch) / -dn);
  }
  return scale;
}

}  // namespace

ImplicitStart implicit_start(model::Model& model, solver::Solver& solver,
                             const loading::SpecimenBoundary& boundary, const loading::Stage& stage,
                             double confining_stress) {
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
  double done = 0.0, total = 0.0, time = 0.0, load_done = 0.0;
  const double v = stage.platen_velocity;
  std::vector<std::array<double, 3>> load(nb);
  // Each open contact that closes on the way costs one more solve (it enters K there).
  const int most_solves = increments + 200;
  int solves = 0;
  // Phase 0 applies the confinement with the platens held, as the explicit steps do before the
  // platen has moved; phase 1 moves the platen. One driver per phase keeps the active set exact.
  bool stopped = false;
  for (int phase = confining_stress != 0.0 ? 0 : 1; phase < 2 && !stopped; ++phase)
    for (int k = 0, phase_solves = 0; k < increments && phase_solves < most_solves && !stopped;
         ++solves, ++phase_solves) {
      model::refresh_world(model);
      // Load case: the confining traction on the lateral edges as they now lie (follower load).
      boundary.apply_confinement(model, confining_stress);
      for (std::size_t b = 0; b < nb; ++b) load[b] = {bl.fx[b], bl.fy[b], bl.moment[b]};
      try {
        r = solver::elastic_response(model, solver.laws(), unit, load,
                                     phase == 0 ? 1.0 - load_done : 0.0);
      } catch (const solver::ElasticResponseError& e) {
        if (solves == 0) throw;
        // Contacts that closed on the way left a mechanism (a disc on point contacts): the
        // explicit steps take over from the last solved state.
        s.limit = fmt::format("stopped after {} solves: {}", solves, e.what());
        stopped = true;
        continue;
      }
      s.passes += r.passes;
      s.solve_seconds += r.factorise_seconds;
      // Axial stress per metre of platen displacement, as measure_specimen takes it.
      const auto axial = [&](const solver::ElasticCase& c) {
        return measure::platen_stress(c.force[top][1], c.force[bottom][1], boundary,
                                      model.thickness);
      };
      const double stress_per_m = axial(r.unit);
      if (solves == 0) {
        if (r.load_reach < 1.0)
          throw solver::ElasticResponseError(fmt::format(
              "the confining stress alone takes a contact out of its elastic regime (at {:.3g} of "
              "it): start without implicit_start",
              r.load_reach));
        s.dofs = r.dofs;
        s.active_contacts = r.active_contacts;
        s.reach = r.reach;
        s.modulus = stress_per_m * boundary.height();
        if (r.limiting_contact < model.contacts.size()) {
          const model::Contact& c = model.contacts[r.limiting_contact];
          s.limit =
              fmt::format("first contact out of its elastic regime: blocks {} and {}", c.a, c.b);
        }
        total = jump_target(fraction * r.reach, stage, boundary.height(),
                            (stage.end.axial_stress - axial(r.load)) / stress_per_m, s.limit);
        if (!std::isfinite(total))
          throw solver::ElasticResponseError(
              "nothing limits the implicit elastic start: no contact ever leaves its elastic "
              "regime and the stage has no end_axial_strain or end_axial_stress");
      }
      // Equal parts of what is left of the load (phase 0) or of the platen's way, the platen's
      // within the elastic reach from here (phase 1).
      const double left = increments - k;
      double d = phase == 1 ? std::min((total - done) / left, fraction * r.reach) : 0.0;
      double part = phase == 0 ? (1.0 - load_done) / left : 0.0;
      const double scale = closing_scale(model, r, d, part);
      if (scale < 1.0) {
        d *= scale;
        part *= scale;
        ++s.closings;
      } else {
        ++k;
      }
      std::vector<double> dx(nb), dy(nb), dt(nb);
      for (std::size_t b = 0; b < nb; ++b) {
        dx[b] = d * r.unit.ux[b] + part * r.load.ux[b];
        dy[b] = d * r.unit.uy[b] + part * r.load.uy[b];
        dt[b] = d * r.unit.utheta[b] + part * r.load.utheta[b];
      }
      const double t = program_time(done + d, v, stage.ramp_time);
      solver.displace(dx, dy, dt, t - time);
      done += d;
      load_done += part;
      time = t;
      s.stress += stress_per_m * d + part * axial(r.load);
      s.solves = solves + 1;
    }
  s.displacement = done;
  s.time = time;
  // The blocks go on moving as the linear response does at the platen's speed: no start-up wave.
  const double speed =
      stage.ramp_time > 0.0 && time < stage.ramp_time ? v * time / stage.ramp_time : v;
  for (std::size_t b = 0; b < nb; ++b) {
    if (bl.prescribed[b]) continue;
    bl.vx[b] = speed * r.unit.ux[b];
    bl.vy[b] = speed * r.unit.uy[b];
    bl.omega[b] = speed * r.unit.utheta[b];
  }
  return s;
}

io::Json implicit_start_json(const ImplicitStart& i) {
  return {{"platen_displacement_m", io::rounded(i.displacement, 8)},
          // JSON has no infinity: a reach nothing limits (no contact loaded yet) is null.
          {"elastic_reach_m", io::rounded(i.reach, 8)},
          {"axial_stress_Pa", io::rounded(i.stress, 8)},
          {"linear_youngs_modulus_Pa", io::rounded(i.modulus, 8)},
          {"stage_time_s", io::rounded(i.time, 8)},
          {"dofs", i.dofs},
          {"active_contacts", i.active_contacts},
          {"solves", i.solves},
          {"closings", i.closings},
          {"factorisations", i.passes},
          {"solve_wall_time_s", io::fixed(i.solve_seconds, 4)},
          {"limit", i.limit}};
}

}  // namespace vorodec::run
