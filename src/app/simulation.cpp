#include "vorodec/app/simulation.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>

#include "damage_output.hpp"
#include "implicit_start.hpp"
#include "progress.hpp"
#include "vorodec/geometry/grains.hpp"
#include "vorodec/io/csv_writer.hpp"
#include "vorodec/io/specimen_file.hpp"
#include "vorodec/io/vtk_writer.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/loading/stage_control.hpp"
#include "vorodec/measure/cycles.hpp"
#include "vorodec/measure/damage.hpp"
#include "vorodec/measure/failure_stages.hpp"
#include "vorodec/measure/grain_cracks.hpp"
#include "vorodec/measure/specimen.hpp"
#include "vorodec/model/build.hpp"
#include "vorodec/model/contact_geometry.hpp"
#include "vorodec/solver/elastic_response.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::app {

using model::Group;

geometry::Tessellation make_specimen(const io::ModelConfig& cfg) {
  if (cfg.specimen_file) return io::read_specimen(*cfg.specimen_file);
  if (cfg.grains) return geometry::tessellate_grains(cfg.tessellation, cfg.grains->settings);
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

// Law groups after the joints (0) and platens (1) of a grain-based specimen: the default
// transgranular law, each mineral's own, each mineral pair's own; and the table choosing them.
void add_grain_laws(const io::GrainConfig& g, const geometry::Tessellation& tess,
                    std::uint64_t seed, std::vector<std::unique_ptr<laws::LawGroup>>& groups,
                    solver::GrainLaws& table) {
  const auto add = [&](const io::LawChoice& choice) {
    groups.push_back(laws::find_law(choice.name)->make(choice.params, seed));
    return static_cast<int>(groups.size() - 1);
  };
  const std::size_t n = g.minerals.size();
  table.minerals = n;
  table.grain_of_block = tess.block_grain;
  table.mineral_of_grain = tess.grain_mineral;
  const int trans = add(g.transgranular);
  table.transgranular.assign(n, trans);
  for (std::size_t m = 0; m < n; ++m)
    if (g.inside[m]) table.transgranular[m] = add(*g.inside[m]);
  table.intergranular.assign(n * n, 0);
  for (const auto& p : g.pairs)
    table.intergranular[p.a * n + p.b] = table.intergranular[p.b * n + p.a] = add(p.law);
}

const io::Mineral& block_mineral(const io::GrainConfig& g, const geometry::Tessellation& t,
                                 std::size_t block) {
  const auto grain = static_cast<std::size_t>(t.block_grain[block]);
  return g.minerals[static_cast<std::size_t>(t.grain_mineral[grain])];
}

std::vector<double> block_densities(const io::GrainConfig& g, const geometry::Tessellation& t) {
  std::vector<double> density;
  for (std::size_t b = 0; b < t.block_grain.size(); ++b)
    density.push_back(block_mineral(g, t, b).density);
  return density;
}

}  // namespace

PreparedModel prepare_model(const io::ModelConfig& cfg, const geometry::Tessellation& tess) {
  PreparedModel s;
  const double d = cfg.rounding_length > 0 ? cfg.rounding_length : 0.05 * mean_edge(tess);
  std::optional<model::DeformableBuild> deformable;
  if (cfg.deformable.enabled) {
    deformable = model::DeformableBuild{
        cfg.deformable.zone_size, {cfg.deformable.youngs_modulus, cfg.deformable.poisson_ratio}};
    if (cfg.grains)  // each zone takes its mineral's elasticity
      for (std::size_t b = 0; b < tess.block_grain.size(); ++b) {
        const io::Mineral& m = block_mineral(*cfg.grains, tess, b);
        deformable->block_material.push_back({m.youngs_modulus, m.poisson_ratio});
      }
  }
  const std::vector<double> density =
      cfg.grains ? block_densities(*cfg.grains, tess) : std::vector<double>{};
  s.model = std::make_unique<model::Model>(
      model::build_model(tess, {cfg.density, d, true, density}, deformable));
  std::vector<std::unique_ptr<laws::LawGroup>> groups;
  for (const io::LawChoice* choice : {&cfg.joints, &cfg.platens})
    groups.push_back(laws::find_law(choice->name)->make(choice->params, cfg.seed));
  solver::LawTable table;
  if (cfg.grains) add_grain_laws(*cfg.grains, tess, cfg.seed, groups, table.grains);
  const auto set = [&](Group a, Group b, int law) {
    table.law[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = law;
    table.law[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = law;
  };
  set(Group::specimen, Group::specimen, 0);
  set(Group::specimen, Group::bottom_platen, 1);
  set(Group::specimen, Group::top_platen, 1);
  for (Group p : {Group::bottom_platen, Group::top_platen}) {
    table.bond[static_cast<std::size_t>(p)][0] = cfg.platens_bonded;
    table.bond[0][static_cast<std::size_t>(p)] = cfg.platens_bonded;
  }
  solver::SolverSettings settings = cfg.solver;
  if (settings.contact_tolerance <= 0) settings.contact_tolerance = d;
  s.solver = std::make_unique<solver::Solver>(*s.model, std::move(groups), table, settings);
  s.solver->initialise();
  return s;
}

namespace {

io::VtkFrame make_frame(const model::Model& m, const solver::Solver& solver,
                        const geometry::Tessellation& tess) {
  io::VtkFrame f;
  f.time = solver.time();
  const auto& bl = m.blocks;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    f.block_offsets.push_back(static_cast<std::uint32_t>(f.block_points.size()));
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c) {
      if (bl.deformable[b]) {
        const auto g = static_cast<std::size_t>(m.zoning.corner_gp[c]);
        f.block_points.push_back({m.zoning.x[g], m.zoning.y[g]});
      } else {
        f.block_points.push_back(bl.to_world(b, bl.corner[c]));
      }
    }
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
  const model::Zoning& z = m.zoning;
  for (std::size_t i = 0; i < z.zones.size(); ++i) {
    for (const std::uint32_t g : z.zones[i].gp) f.zone_points.push_back({z.x[g], z.y[g]});
    f.zone_block.push_back(static_cast<std::int32_t>(z.zone_block[i]));
    const model::ZoneStress& s = z.stress[i];
    f.zone_stress.push_back({s.xx, s.yy, s.xy, s.zz});
    f.zone_strain.push_back({z.strain[i][0], z.strain[i][1], 0.5 * z.strain[i][2]});
  }
  for (const laws::CrackEvent& e : solver.cracks()) {
    const model::Point mid{e.x, e.y}, t{-e.ny * 0.5 * e.length, e.nx * 0.5 * e.length};
    f.crack_begin.push_back(mid - t);
    f.crack_end.push_back(mid + t);
    f.crack_type.push_back(e.type == laws::ContactEvent::tensile_failure ? 1 : 2);
    f.crack_time.push_back(e.time);
    if (!tess.block_grain.empty())
      f.crack_class.push_back(static_cast<std::int32_t>(measure::crack_class(e, tess.block_grain)) +
                              1);
  }
  if (!tess.block_grain.empty()) {
    for (std::size_t b = 0; b < bl.size(); ++b) {
      const bool specimen = b < tess.block_grain.size();
      const std::int32_t g = specimen ? tess.block_grain[b] : -1;
      f.block_grain.push_back(g);
      f.block_mineral.push_back(specimen ? tess.grain_mineral[static_cast<std::size_t>(g)] : -1);
    }
  }
  return f;
}

// Grain-based specimens add the crack class (1-4, measure::kCrackClassNames) before the type.
void write_cracks(const std::filesystem::path& file, const std::vector<laws::CrackEvent>& cracks,
                  std::span<const std::int32_t> grain_of_block) {
  std::vector<std::string> header{"time",   "x",       "y",      "orientation_deg",
                                  "length", "block_a", "block_b"};
  if (!grain_of_block.empty()) header.push_back("class");
  header.push_back("type");
  io::CsvWriter csv(file, header);
  for (const auto& e : cracks) {
    double v[] = {e.time,   e.x,         e.y,         measure::crack_orientation_deg(e),
                  e.length, double(e.a), double(e.b), 0.0};
    std::size_t n = 7;
    if (!grain_of_block.empty()) v[n++] = double(measure::crack_class(e, grain_of_block) + 1);
    csv.row(std::span<const double>(v, n),
            e.type == laws::ContactEvent::tensile_failure ? "tensile" : "shear");
  }
}

void write_cycles(const std::filesystem::path& file,
                  const std::vector<measure::CycleMeasures>& cycles) {
  const std::vector<std::string> header{"cycle",
                                        "upper_target_Pa",
                                        "upper_reached_Pa",
                                        "stalled",
                                        "secant_modulus_Pa",
                                        "poisson_ratio",
                                        "input_work_J_m3",
                                        "recovered_work_J_m3",
                                        "dissipated_work_J_m3",
                                        "dissipated_total_J_m3",
                                        "residual_strain"};
  io::CsvWriter csv(file, header);
  for (const auto& c : cycles) {
    const double v[] = {double(c.cycle),       c.upper_target,   c.upper_reached,
                        c.stalled ? 1.0 : 0.0, c.secant_modulus, c.poisson_ratio,
                        c.input_work,          c.recovered_work, c.dissipated_work,
                        c.dissipated_total,    c.residual_strain};
    csv.row(v);
  }
}

// Grain-based specimens: requested and achieved mineral area fractions, and the crack classes.
std::string grain_summary(const io::ModelConfig& cfg, const geometry::Tessellation& tess,
                          const measure::GrainCracks& g) {
  if (!cfg.grains) return "";
  double total = 0;
  for (const double a : tess.mineral_area) total += a;
  std::string minerals;
  for (std::size_t m = 0; m < cfg.grains->minerals.size(); ++m)
    minerals +=
        fmt::format("{}\n    \"{}\": {{\"requested\": {:.6g}, \"achieved\": {:.6g}}}", m ? "," : "",
                    cfg.grains->minerals[m].name, cfg.grains->minerals[m].fraction,
                    m < tess.mineral_area.size() ? tess.mineral_area[m] / total : 0.0);
  std::string cracks;
  for (std::size_t k = 0; k < measure::kCrackClasses; ++k)
    cracks += fmt::format("{}\n    \"{}\": {{\"count\": {}, \"length_m\": {:.6g}}}", k ? "," : "",
                          measure::kCrackClassNames[k], g.count[k], g.length[k]);
  return fmt::format(
      "  \"grains\": {},\n  \"mineral_area_fractions\": {{{}\n  }},\n"
      "  \"crack_classes\": {{{}\n  }},\n",
      tess.grain_mineral.size(), minerals, cracks);
}

std::string implicit_json(const std::optional<ImplicitStart>& i) {
  if (!i) return "";
  return fmt::format(
      ",\n  \"implicit_start\": {{\"platen_displacement_m\": {:.8g}, "
      "\"elastic_reach_m\": {}, \"axial_stress_Pa\": {:.8g}, "
      "\"linear_youngs_modulus_Pa\": {:.8g}, \"stage_time_s\": {:.8g}, \"dofs\": {}, "
      "\"active_contacts\": {}, \"solves\": {}, \"closings\": {}, \"factorisations\": {}, "
      "\"solve_wall_time_s\": {:.4f}, \"limit\": \"{}\"}}",
      // JSON has no infinity: a reach nothing limits (no contact loaded yet) is null.
      i->displacement, std::isfinite(i->reach) ? fmt::format("{:.8g}", i->reach) : "null",
      i->stress, i->modulus, i->time, i->dofs, i->active_contacts, i->solves, i->closings,
      i->passes, i->solve_seconds, i->limit);
}

void write_summary(const std::filesystem::path& file, const io::ModelConfig& cfg,
                   const RunSummary& s, std::size_t initial_contacts, double dt, std::size_t broken,
                   const std::string& grains) {
  std::ofstream out(file);
  const auto& f = s.failure_stages;
  const std::string stages =
      f.valid ? fmt::format(
                    "{{\"crack_initiation_stress_Pa\": {:.8g}, "
                    "\"accelerating_crack_growth_stress_Pa\": {:.8g}, "
                    "\"peak_stress_Pa\": {:.8g}}}",
                    f.crack_initiation_stress, f.accelerating_stress, f.peak_stress)
              : "null";
  out << fmt::format(
      "{{\n  \"model\": \"{}\",\n  \"status\": \"{}\",\n  \"peak_stress_Pa\": {:.8g},\n"
      "  \"tensile_strength_Pa\": {:.8g},\n  \"failure_stages\": {},\n"
      "  \"cycles\": {},\n"
      "  \"youngs_modulus_Pa\": {:.8g},\n  \"poisson_ratio\": {:.6g},\n"
      "  \"elastic_fit\": \"tangent over 40-60 % of peak, plane-strain apparent values\",\n"
      "  \"cracks\": {{\"tensile\": {}, \"shear\": {}}},\n{}  \"failure_rate\": {:.6g},\n"
      "  \"blocks\": {},\n  \"initial_contacts\": {},\n  \"time_step_s\": {:.6g},\n"
      "  \"steps\": {},\n  \"wall_time_s\": {:.3f}{}{}\n}}\n",
      cfg.file.filename().string(), s.status, s.peak_stress, s.tensile_strength, stages,
      s.cycles.size(), s.youngs_modulus, s.poisson_ratio, s.cracks_tensile, s.cracks_shear, grains,
      initial_contacts ? double(broken) / double(initial_contacts) : 0.0, s.blocks,
      initial_contacts, dt, s.steps, s.wall_seconds,
      s.zones ? fmt::format(",\n  \"zones\": {},\n  \"zone_stress_Pa\": {{\"xx\": {:.8g}, "
                            "\"yy\": {:.8g}, \"xy\": {:.8g}}}",
                            s.zones, s.zone_stress_xx, s.zone_stress_yy, s.zone_stress_xy)
              : std::string(),
      implicit_json(s.implicit_start));
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

  std::vector<std::string> header{"step",
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
                                  "breakage_energy"};
  // Deformable specimens: the zones' area-weighted mean stress (compression positive, Pa).
  const bool zoned = !model.zoning.empty();
  if (zoned) header.insert(header.end(), {"zone_stress_xx", "zone_stress_yy", "zone_stress_xy"});
  const bool grains = !specimen.block_grain.empty();
  if (grains) {
    for (const auto name : measure::kCrackClassNames) header.emplace_back(name);
    for (const auto name : measure::kCrackClassNames)
      header.push_back(std::string(name) + "_length");
  }
  // What an adaptive velocity stage did (any stage: the applied speed and the ratio it steers by).
  header.insert(header.end(), {"platen_velocity", "unbalanced_force_ratio"});
  header.emplace_back("stage");
  io::CsvWriter history(options.out / "history.csv", header);
  std::unique_ptr<io::VtkSeriesWriter> vtk;
  if (options.write_vtk) vtk = std::make_unique<io::VtkSeriesWriter>(options.out / "vtk");
  DamageOutput damage(model, cfg.output.damage_grid_cell, options.out);

  std::vector<double> h_strain, h_stress, h_lateral, h_failure;
  std::vector<measure::HistoryPoint> rows;
  int current_stage = 0;
  std::size_t n_tensile = 0, n_shear = 0;
  const auto count_cracks = [&] {
    n_tensile = n_shear = 0;
    for (const auto& e : solver.cracks())
      (e.type == laws::ContactEvent::tensile_failure ? n_tensile : n_shear)++;
  };
  measure::SpecimenState state = measure::measure_specimen(model, boundary, solver);
  double v = 0.0;  // m/s, top platen
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
        solver.contact_strain_energy() + (zoned ? solver.zone_strain_energy() : 0.0),
        solver.kinetic_energy(),
        e.damping,
        e.slip,
        e.breakage};
    std::vector<double> full(std::begin(row), std::end(row));
    if (zoned) {
      const model::ZoneStress m = model::mean_stress(model, Group::specimen);
      full.insert(full.end(), {-m.xx, -m.yy, -m.xy});
    }
    if (grains) {
      const measure::GrainCracks g = measure::grain_cracks(solver.cracks(), specimen.block_grain);
      for (const std::size_t n : g.count) full.push_back(double(n));
      full.insert(full.end(), g.length.begin(), g.length.end());
    }
    full.insert(full.end(), {v, solver.unbalanced_force_ratio()});
    history.row(full, stage);
    h_strain.push_back(state.axial_strain);
    h_stress.push_back(state.axial_stress);
    h_lateral.push_back(state.lateral_strain);
    h_failure.push_back(row[8]);
    rows.push_back({state.axial_strain, state.axial_stress, state.lateral_strain, current_stage});
  };
  // A VTK output time: rose.csv row always, VTK frame (with the damage fields) unless --no-vtk.
  const auto output_frame = [&](const std::string& stage) {
    io::VtkFrame frame;
    if (vtk) frame = make_frame(model, solver, specimen);
    damage.output_time(model, solver, stage, state.axial_stress, vtk ? &frame : nullptr);
    if (vtk) vtk->write(frame);
  };

  RunSummary summary;
  summary.blocks = model.blocks.size();
  summary.status = "finished";
  const auto& stages = cfg.load_path.stages;
  Progress progress(options.progress, stages.size());
  const long step_limit = options.max_steps > 0 ? options.max_steps : cfg.max_steps;
  double peak = 0.0, trough = 0.0;
  std::vector<double> good_x, good_y, good_t;  // last state that passed the stability check
  std::vector<double> good_gx, good_gy;        // and its gridpoints
  std::vector<bool> stalled(stages.size(), false);
  bool stop = false;
  int resume_at = -1;  // a stalled cyclic block resumes here after its unloading
  try {
    for (std::size_t si = 0; si < stages.size() && !stop; ++si) {
      const loading::Stage& st = stages[si];
      current_stage = static_cast<int>(si);
      const double t0 = solver.time();
      loading::StageControl control(st, v, state.axial_stress, state.axial_strain);
      record(st.name + ":start");
      if (st.implicit_start) {
        try {
          summary.implicit_start = implicit_start(model, solver, boundary, st, sigma3);
        } catch (const solver::ElasticResponseError& e) {
          throw io::ModelFileError(fmt::format("{}: {}", cfg.implicit_start_where, e.what()),
                                   fmt::format("stage[{}].implicit_start", si), e.what());
        }
        state = measure::measure_specimen(model, boundary, solver);
        peak = std::max(peak, state.axial_stress);
        record(st.name + ":implicit");
      }
      for (;;) {
        if (solver.steps() >= step_limit) {
          summary.status = options.max_steps > 0 ? "stopped at --max-steps" : "step limit";
          summary.exit_code = options.max_steps > 0 ? 0 : 4;
          stop = true;
          break;
        }
        const double ts = solver.time() - t0;
        // Adaptive speed: after the ramp, every interval_steps, from the last step's forces.
        if (st.adaptive.enabled && ts >= st.ramp_time &&
            solver.steps() % st.adaptive.interval_steps == 0)
          control.adapt(solver.unbalanced_force_ratio(), ts, solver.dt());
        v = control.platen_velocity(
            ts, state.axial_stress,
            solver.contact_stiffness_on(static_cast<std::size_t>(boundary.top_platen())),
            solver.dt(), boundary.width());
        boundary.set_platen_velocity(model, v);
        boundary.apply_confinement(model, sigma3);
        solver.step();
        state = measure::measure_specimen(model, boundary, solver);
        if (solver.steps() % 100 == 0) {
          solver.check_stability();
          good_x = model.blocks.x;
          good_y = model.blocks.y;
          good_t = model.blocks.theta;
          good_gx = model.zoning.x;
          good_gy = model.zoning.y;
        }
        peak = std::max(peak, state.axial_stress);
        trough = std::min(trough, state.axial_stress);
        const bool row = solver.steps() % cfg.output.history_steps == 0;
        if (row) record(st.name);
        if (solver.steps() % cfg.output.vtk_steps == 0) output_frame(st.name);
        const loading::StageOutcome outcome =
            control.judge({solver.time() - t0, state.axial_stress, state.axial_strain, row});
        progress.update(si, control.fraction(), state.axial_stress, peak, solver.steps());
        if (outcome == loading::StageOutcome::stalled) {
          stalled[si] = true;
          resume_at = st.block_end;
        }
        if (outcome != loading::StageOutcome::running) break;
      }
      record(st.name + (stalled[si] ? ":stalled" : ":end"));
      output_frame(st.name + (stalled[si] ? ":stalled" : ":end"));
      if (resume_at >= 0 && st.phase == loading::CyclePhase::unloading) {
        si = static_cast<std::size_t>(resume_at) - 1;
        resume_at = -1;
      }
    }
  } catch (const solver::InstabilityError& e) {
    summary.exit_code = 3;
    summary.status = fmt::format("unstable: {}", e.what());
    if (!good_x.empty()) {  // restore the last state that passed the check before writing it
      model.blocks.x = good_x;
      model.blocks.y = good_y;
      model.blocks.theta = good_t;
      model.zoning.x = good_gx;
      model.zoning.y = good_gy;
      model::refresh_world(model);  // the frame and the damage measures read world positions
    }
    output_frame("unstable");
  }
  progress.finish();
  history.flush();
  count_cracks();
  write_cracks(options.out / "cracks.csv", solver.cracks(), specimen.block_grain);
  // A pulled specimen (direct tension): its elastic constants come from the tensile branch.
  const double sense = -trough > peak ? -1.0 : 1.0;
  for (auto* h : {&h_strain, &h_stress, &h_lateral})
    for (double& x : *h) x *= sense;
  const bool brazilian =
      cfg.tessellation.outline.kind == geometry::OutlineKind::disc && !cfg.specimen_file;
  // A disc's platen stress and strain define no Young's modulus: none is reported.
  const auto ec = brazilian ? measure::ElasticConstants{}
                            : measure::elastic_constants(h_strain, h_stress, h_lateral);
  summary.peak_stress = peak;
  // Brazilian test (disc between platens): sigma_t = 2 F / (pi D t), and the axial stress is
  // F / (D t). Direct tension: the largest pull.
  if (brazilian)
    summary.tensile_strength = 2.0 / M_PI * peak;
  else if (trough < 0)
    summary.tensile_strength = -trough;
  summary.failure_stages = measure::failure_stages(h_strain, h_stress, h_failure);
  summary.cycles = measure::cycle_measures(rows, stages, stalled);
  if (!summary.cycles.empty()) write_cycles(options.out / "cycles.csv", summary.cycles);
  summary.youngs_modulus = ec.youngs_modulus;
  summary.zones = model.zoning.zones.size();
  if (zoned) {
    const model::ZoneStress m = model::mean_stress(model, Group::specimen);
    summary.zone_stress_xx = -m.xx;
    summary.zone_stress_yy = -m.yy;
    summary.zone_stress_xy = -m.xy;
  }
  summary.poisson_ratio = ec.poisson_ratio;
  summary.steps = solver.steps();
  summary.contacts = model.contacts.size();
  summary.cracks_tensile = n_tensile;
  summary.cracks_shear = n_shear;
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  write_summary(
      options.out / "summary.json", cfg, summary, solver.initial_bonded_contacts(), solver.dt(),
      n_tensile + n_shear,
      grain_summary(cfg, specimen, measure::grain_cracks(solver.cracks(), specimen.block_grain)));
  return summary;
}

}  // namespace vorodec::app
