#include "vorodec/app/simulation.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>

#include "damage_output.hpp"
#include "progress.hpp"
#include "vorodec/io/csv_writer.hpp"
#include "vorodec/io/specimen_file.hpp"
#include "vorodec/io/vtk_writer.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/measure/damage.hpp"
#include "vorodec/measure/specimen.hpp"
#include "vorodec/model/build.hpp"
#include "vorodec/model/contact_geometry.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::app {

using model::Group;

geometry::Tessellation make_specimen(const io::ModelConfig& cfg) {
  if (cfg.specimen_file) return io::read_specimen(*cfg.specimen_file);
  return geometry::tessellate(cfg.tessellation);
}

namespace {

double mean_edge(const geometry::Tessellation& t) {
  double sum = 0;
  std::size_t n = 0;
  for (const auto& b : t.blocks)
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto d = t.vertices[b[(i + 1) % b.size()]] - t.vertices[b[i]];
      sum += std::sqrt(dot(d, d));
      ++n;
    }
  return n ? sum / static_cast<double>(n) : 0.0;
}

}  // namespace

PreparedModel prepare_model(const io::ModelConfig& cfg, const geometry::Tessellation& tess) {
  PreparedModel s;
  const double d = cfg.rounding_length > 0 ? cfg.rounding_length : 0.05 * mean_edge(tess);
  s.model = std::make_unique<model::Model>(model::build_model(tess, {cfg.density, d, true}));
  std::vector<std::unique_ptr<laws::LawGroup>> groups;
  for (const io::LawChoice* choice : {&cfg.joints, &cfg.platens})
    groups.push_back(laws::find_law(choice->name)->make(choice->params, cfg.seed));
  solver::LawTable table;
  const auto set = [&](Group a, Group b, int law) {
    table.law[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = law;
    table.law[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = law;
  };
  set(Group::specimen, Group::specimen, 0);
  set(Group::specimen, Group::bottom_platen, 1);
  set(Group::specimen, Group::top_platen, 1);
  solver::SolverSettings settings = cfg.solver;
  if (settings.contact_tolerance <= 0) settings.contact_tolerance = d;
  s.solver = std::make_unique<solver::Solver>(*s.model, std::move(groups), table, settings);
  s.solver->initialise();
  return s;
}

namespace {

io::VtkFrame make_frame(const model::Model& m, const solver::Solver& solver) {
  io::VtkFrame f;
  f.time = solver.time();
  const auto& bl = m.blocks;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    f.block_offsets.push_back(static_cast<std::uint32_t>(f.block_points.size()));
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c)
      f.block_points.push_back(bl.to_world(b, bl.corner[c]));
    f.block_id.push_back(static_cast<std::int32_t>(b));
    f.block_group.push_back(static_cast<std::int32_t>(bl.group[b]));
    f.block_velocity.push_back({bl.vx[b], bl.vy[b]});
    f.block_displacement.push_back({bl.x[b] - bl.x0[b], bl.y[b] - bl.y0[b]});
  }
  f.block_offsets.push_back(static_cast<std::uint32_t>(f.block_points.size()));
  for (model::Contact c : m.contacts) {
    const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
    f.contact_point.push_back(model::contact_frame(bl, c).point);
    f.contact_a.push_back({bl.x[a], bl.y[a]});
    f.contact_b.push_back({bl.x[b], bl.y[b]});
    f.contact_normal_force.push_back(c.fn);
    f.contact_shear_force.push_back(c.fs);
    f.contact_state.push_back(static_cast<std::int32_t>(c.state));
  }
  for (const laws::CrackEvent& e : solver.cracks()) {
    const model::Point mid{e.x, e.y}, t{-e.ny * 0.5 * e.length, e.nx * 0.5 * e.length};
    f.crack_begin.push_back(mid - t);
    f.crack_end.push_back(mid + t);
    f.crack_type.push_back(e.type == laws::ContactEvent::tensile_failure ? 1 : 2);
    f.crack_time.push_back(e.time);
  }
  return f;
}

void write_cracks(const std::filesystem::path& file, const std::vector<laws::CrackEvent>& cracks) {
  const std::vector<std::string> header{"time",   "x",       "y",       "orientation_deg",
                                        "length", "block_a", "block_b", "type"};
  io::CsvWriter csv(file, header);
  for (const auto& e : cracks) {
    const double v[] = {e.time,   e.x,         e.y,        measure::crack_orientation_deg(e),
                        e.length, double(e.a), double(e.b)};
    csv.row(v, e.type == laws::ContactEvent::tensile_failure ? "tensile" : "shear");
  }
}

void write_summary(const std::filesystem::path& file, const io::ModelConfig& cfg,
                   const RunSummary& s, std::size_t initial_contacts, double dt,
                   std::size_t broken) {
  std::ofstream out(file);
  out << fmt::format(
      "{{\n  \"model\": \"{}\",\n  \"status\": \"{}\",\n  \"peak_stress_Pa\": {:.8g},\n"
      "  \"youngs_modulus_Pa\": {:.8g},\n  \"poisson_ratio\": {:.6g},\n"
      "  \"elastic_fit\": \"tangent over 40-60 % of peak, plane-strain apparent values\",\n"
      "  \"cracks\": {{\"tensile\": {}, \"shear\": {}}},\n  \"failure_rate\": {:.6g},\n"
      "  \"blocks\": {},\n  \"initial_contacts\": {},\n  \"time_step_s\": {:.6g},\n"
      "  \"steps\": {},\n  \"wall_time_s\": {:.3f}\n}}\n",
      cfg.file.filename().string(), s.status, s.peak_stress, s.youngs_modulus, s.poisson_ratio,
      s.cracks_tensile, s.cracks_shear,
      initial_contacts ? double(broken) / double(initial_contacts) : 0.0, s.blocks,
      initial_contacts, dt, s.steps, s.wall_seconds);
}

}  // namespace

std::string describe_contacts(const io::ModelConfig& cfg, const geometry::Tessellation& specimen) {
  PreparedModel s = prepare_model(cfg, specimen);
  std::string out = "contacts: id block_a block_b length_m law";
  const auto& groups = s.solver->laws();
  for (auto n : groups[0]->property_names()) out += fmt::format(" {}", n);
  out += '\n';
  std::vector<std::size_t> local(groups.size(), 0);
  for (const auto& c : s.model->contacts) {
    const auto props = groups[c.law]->properties(local[c.law]++);
    out += fmt::format("{} {} {} {:.9g} {}", c.id, c.a, c.b, c.length, groups[c.law]->name());
    for (double p : props) out += fmt::format(" {:.9g}", p);
    out += '\n';
  }
  return out;
}

RunSummary run_model(const io::ModelConfig& cfg, const geometry::Tessellation& specimen,
                     const RunOptions& options) {
  const auto wall0 = std::chrono::steady_clock::now();
  PreparedModel setup = prepare_model(cfg, specimen);
  model::Model& model = *setup.model;
  solver::Solver& solver = *setup.solver;
  const loading::SpecimenBoundary boundary(model);
  const double sigma3 = cfg.load_path.confining_stress;

  const std::vector<std::string> header{"step",
                                        "time",
                                        "axial_strain",
                                        "axial_stress",
                                        "lateral_strain",
                                        "volumetric_strain",
                                        "cracks_tensile",
                                        "cracks_shear",
                                        "failure_rate",
                                        "damage_density",
                                        "p21",
                                        "boundary_work",
                                        "strain_energy",
                                        "kinetic_energy",
                                        "damping_energy",
                                        "friction_energy",
                                        "breakage_energy",
                                        "stage"};
  io::CsvWriter history(options.out / "history.csv", header);
  std::unique_ptr<io::VtkSeriesWriter> vtk;
  if (options.write_vtk) vtk = std::make_unique<io::VtkSeriesWriter>(options.out / "vtk");
  DamageOutput damage(model, cfg.output.damage_grid_cell, options.out);

  std::vector<double> h_strain, h_stress, h_lateral;
  std::size_t n_tensile = 0, n_shear = 0;
  const auto count_cracks = [&] {
    n_tensile = n_shear = 0;
    for (const auto& e : solver.cracks())
      (e.type == laws::ContactEvent::tensile_failure ? n_tensile : n_shear)++;
  };
  measure::SpecimenState state = measure::measure_specimen(model, boundary, solver);
  const auto record = [&](const std::string& stage) {
    count_cracks();
    const auto& e = solver.energy();
    const double broken = double(n_tensile + n_shear);
    const measure::DamageState dmg = damage.measure(model, solver);
    const double row[] = {
        double(solver.steps()),
        solver.time(),
        state.axial_strain,
        state.axial_stress,
        state.lateral_strain,
        state.volumetric_strain,
        double(n_tensile),
        double(n_shear),
        solver.initial_bonded_contacts() ? broken / double(solver.initial_bonded_contacts()) : 0.0,
        dmg.damage_density,
        dmg.p21,
        e.boundary_work,
        solver.contact_strain_energy(),
        solver.kinetic_energy(),
        e.damping,
        e.slip,
        e.breakage};
    history.row(row, stage);
    h_strain.push_back(state.axial_strain);
    h_stress.push_back(state.axial_stress);
    h_lateral.push_back(state.lateral_strain);
  };
  // A VTK output time: rose.csv row always, VTK frame (with the damage fields) unless --no-vtk.
  const auto output_frame = [&](const std::string& stage) {
    io::VtkFrame frame;
    if (vtk) frame = make_frame(model, solver);
    damage.output_time(model, solver, stage, state.axial_stress, vtk ? &frame : nullptr);
    if (vtk) vtk->write(frame);
  };

  RunSummary summary;
  summary.blocks = model.blocks.size();
  summary.status = "finished";
  Progress progress(options.progress, cfg.load_path.stages.size());
  const long step_limit = options.max_steps > 0 ? options.max_steps : cfg.max_steps;
  double v = 0.0, peak = 0.0;
  std::vector<double> good_x, good_y, good_t;  // last state that passed the stability check
  bool stop = false;
  try {
    for (std::size_t si = 0; si < cfg.load_path.stages.size() && !stop; ++si) {
      const loading::Stage& st = cfg.load_path.stages[si];
      const double t0 = solver.time(), v0 = v, eps0 = state.axial_strain;
      double row_peak = 0.0;
      long held = 0, rows_since_peak = 0;
      record(st.name + ":start");
      for (;;) {
        if (solver.steps() >= step_limit) {
          summary.status = options.max_steps > 0 ? "stopped at --max-steps" : "step limit";
          summary.exit_code = options.max_steps > 0 ? 0 : 4;
          stop = true;
          break;
        }
        const double ts = solver.time() - t0;
        if (st.control == loading::Control::platen_velocity) {
          v = ts < st.ramp_time ? v0 + (st.platen_velocity - v0) * ts / st.ramp_time
                                : st.platen_velocity;
        } else {  // servo on the top platen (PFC wall servo, gain 0.8 / (K dt))
          const double k =
              solver.contact_stiffness_on(static_cast<std::size_t>(boundary.top_platen()));
          const double df = (st.target_stress - state.axial_stress) * boundary.width();
          v = k > 0 ? 0.8 * df / (k * solver.dt()) : st.platen_velocity;
          v = std::clamp(v, -st.platen_velocity, st.platen_velocity);
        }
        boundary.set_platen_velocity(model, v);
        boundary.apply_confinement(model, sigma3);
        solver.step();
        state = measure::measure_specimen(model, boundary, solver);
        if (solver.steps() % 100 == 0) {
          solver.check_stability();
          good_x = model.blocks.x;
          good_y = model.blocks.y;
          good_t = model.blocks.theta;
        }
        peak = std::max(peak, state.axial_stress);
        if (solver.steps() % cfg.output.history_steps == 0) record(st.name);
        if (solver.steps() % cfg.output.vtk_steps == 0) output_frame(st.name);
        // End conditions.
        const auto& end = st.end;
        double fraction = 0.0;
        bool done = false;
        if (!std::isnan(end.axial_strain)) {
          const double span = end.axial_strain - eps0;
          fraction = std::max(fraction, span != 0 ? (state.axial_strain - eps0) / span : 1.0);
          done |= span >= 0 ? state.axial_strain >= end.axial_strain
                            : state.axial_strain <= end.axial_strain;
        }
        if (!std::isnan(end.post_peak_fraction) && solver.steps() % cfg.output.history_steps == 0) {
          // Judged on history rows: the peak must lie three rows back, so start-up noise is no
          // peak.
          if (state.axial_stress > row_peak) {
            row_peak = state.axial_stress;
            rows_since_peak = 0;
          } else {
            ++rows_since_peak;
          }
          if (row_peak > 0 && rows_since_peak >= 3) {
            const double drop =
                (1.0 - state.axial_stress / row_peak) / (1.0 - end.post_peak_fraction);
            fraction = std::max(fraction, std::clamp(drop, 0.0, 1.0));
            done |= state.axial_stress < end.post_peak_fraction * row_peak;
          }
        }
        if (!std::isnan(end.stress)) {
          const bool near =
              std::abs(state.axial_stress - end.stress) <= 0.01 * std::max(end.stress, 1e5);
          held = near ? held + 1 : 0;
          if (std::isnan(end.duration)) done |= held >= 200;
        }
        if (!std::isnan(end.duration)) {
          fraction = std::max(fraction, ts / end.duration);
          done |= ts >= end.duration;
        }
        progress.update(si, fraction, state.axial_stress, peak, solver.steps());
        if (done) break;
      }
      record(st.name + ":end");
      output_frame(st.name + ":end");
    }
  } catch (const solver::InstabilityError& e) {
    summary.exit_code = 3;
    summary.status = fmt::format("unstable: {}", e.what());
    if (!good_x.empty()) {  // restore the last state that passed the check before writing it
      model.blocks.x = good_x;
      model.blocks.y = good_y;
      model.blocks.theta = good_t;
      model.blocks.refresh_world();  // the frame and the damage measures read world positions
    }
    output_frame("unstable");
  }
  progress.finish();
  history.flush();
  count_cracks();
  write_cracks(options.out / "cracks.csv", solver.cracks());
  const auto ec = measure::elastic_constants(h_strain, h_stress, h_lateral);
  summary.peak_stress = peak;
  summary.youngs_modulus = ec.youngs_modulus;
  summary.poisson_ratio = ec.poisson_ratio;
  summary.steps = solver.steps();
  summary.contacts = model.contacts.size();
  summary.cracks_tensile = n_tensile;
  summary.cracks_shear = n_shear;
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  write_summary(options.out / "summary.json", cfg, summary, solver.initial_bonded_contacts(),
                solver.dt(), n_tensile + n_shear);
  return summary;
}

}  // namespace vorodec::app
