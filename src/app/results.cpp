#include "results.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ae_output.hpp"
#include "shpb_output.hpp"
#include "vorodec/io/atomic_file.hpp"
#include "vorodec/io/csv_writer.hpp"
#include "vorodec/measure/failure_stages.hpp"
#include "vorodec/measure/grain_cracks.hpp"
#include "vorodec/measure/specimen.hpp"

namespace vorodec::app {

namespace {

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
  std::string text = io::CsvWriter::format_header(header);
  for (const auto& c : cycles) {
    const double v[] = {double(c.cycle),       c.upper_target,   c.upper_reached,
                        c.stalled ? 1.0 : 0.0, c.secant_modulus, c.poisson_ratio,
                        c.input_work,          c.recovered_work, c.dissipated_work,
                        c.dissipated_total,    c.residual_strain};
    text += io::CsvWriter::format_row(v, {});
  }
  io::write_file_atomically(file, text);
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

// Creep stages: the creep step's range, how quasi-static each stayed, and any creep failure.
std::string creep_json(const io::ModelConfig& cfg, const RunSummary& s) {
  if (s.creep.empty()) return "";
  const auto days = [](double t) {
    return std::isnan(t) ? std::string("null") : fmt::format("{:.6g}", t / 86400.0);
  };
  std::string rows;
  for (const auto& [i, r] : s.creep)
    rows += fmt::format(
        "{}\n    {{\"stage\": \"{}\", \"steps\": {}, \"time_step_s\": [{:.6g}, {:.6g}], "
        "\"steps_per_day\": {:.6g}, \"max_kinetic_over_strain_energy\": {:.4g}, "
        "\"failure_onset_days\": {}, \"collapse_days\": {}}}",
        rows.empty() ? "" : ",", cfg.load_path.stages[i].name, r.steps, r.min_time_step,
        r.max_time_step,
        r.steps / ((std::isnan(r.collapse) ? cfg.load_path.stages[i].end.duration : r.collapse) /
                   86400.0),
        r.max_energy_ratio, days(r.failure_onset), days(r.collapse));
  return fmt::format(",\n  \"creep_stages\": [{}\n  ]", rows);
}

// Corrosion stages: the corrosion clock, its steps and the failure time (null: no failure).
std::string corrosion_json(const io::ModelConfig& cfg, const RunSummary& s) {
  if (s.corrosion.empty()) return "";
  std::string rows;
  for (const auto& [i, r] : s.corrosion) {
    const loading::Stage& st = cfg.load_path.stages[i];
    rows += fmt::format(
        "{}\n    {{\"stage\": \"{}\", \"driving_stress_ratio\": {:.6g}, "
        "\"target_stress_Pa\": {:.8g}, \"corrosion_time_s\": {:.10g}, \"failure_time_s\": {}, "
        "\"corrosion_steps\": {}, \"mechanical_steps\": {}, "
        "\"mechanical_steps_per_corrosion_step\": {:.6g}, \"corrosion_step_s\": [{:.6g}, "
        "{:.6g}], \"creep_strain\": {:.6g}, \"broken_transgranular\": {}, "
        "\"broken_intergranular\": {}, \"corroding_bonds\": {}, \"corroding_contacts\": {}}}",
        rows.empty() ? "" : ",", st.name, st.corrosion.driving_stress_ratio, st.target_stress,
        r.time,
        std::isnan(r.failure_time) ? std::string("null") : fmt::format("{:.10g}", r.failure_time),
        r.corrosion_steps, r.mechanical_steps,
        r.corrosion_steps ? double(r.mechanical_steps) / double(r.corrosion_steps) : 0.0,
        r.min_step, r.max_step, r.last_strain - r.first_strain, r.broken_transgranular,
        r.broken_intergranular, r.active_bonds, r.active_contacts);
  }
  return fmt::format(",\n  \"corrosion_stages\": [{}\n  ]", rows);
}

void write_summary(const std::filesystem::path& file, const io::ModelConfig& cfg,
                   const RunSummary& s, std::size_t initial_contacts, double dt, std::size_t broken,
                   const std::string& grains, const std::string& acoustic_emission,
                   const std::string& shpb) {
  const auto& f = s.failure_stages;
  const std::string stages =
      f.valid ? fmt::format(
                    "{{\"crack_initiation_stress_Pa\": {:.8g}, "
                    "\"accelerating_crack_growth_stress_Pa\": {:.8g}, "
                    "\"peak_stress_Pa\": {:.8g}}}",
                    f.crack_initiation_stress, f.accelerating_stress, f.peak_stress)
              : "null";
  io::write_file_atomically(
      file,
      fmt::format(
          "{{\n  \"model\": \"{}\",\n  \"status\": \"{}\",\n  \"peak_stress_Pa\": {:.8g},\n"
          "  \"tensile_strength_Pa\": {:.8g},\n  \"failure_stages\": {},\n"
          "  \"cycles\": {},\n"
          "  \"youngs_modulus_Pa\": {:.8g},\n  \"poisson_ratio\": {:.6g},\n"
          "  \"initial_poisson_ratio\": {:.6g},\n"
          "  \"elastic_fit\": \"tangent over 40-60 % of peak (initial: 10-30 %), plane-strain "
          "apparent values\",\n"
          "  \"cracks\": {{\"tensile\": {}, \"shear\": {}}},\n{}  \"failure_rate\": {:.6g},\n"
          "  \"blocks\": {},\n  \"initial_contacts\": {},\n  \"time_step_s\": {:.6g},\n"
          "  \"steps\": {},\n  \"wall_time_s\": {:.3f}{}{}{}{}{}{}\n}}\n",
          cfg.file.filename().string(), s.status, s.peak_stress, s.tensile_strength, stages,
          s.cycles.size(), s.youngs_modulus, s.poisson_ratio, s.initial_poisson_ratio,
          s.cracks_tensile, s.cracks_shear, grains,
          initial_contacts ? double(broken) / double(initial_contacts) : 0.0, s.blocks,
          initial_contacts, dt, s.steps, s.wall_seconds,
          s.zones ? fmt::format(",\n  \"zones\": {},\n  \"zone_stress_Pa\": {{\"xx\": {:.8g}, "
                                "\"yy\": {:.8g}, \"xy\": {:.8g}}}",
                                s.zones, s.zone_stress_xx, s.zone_stress_yy, s.zone_stress_xy)
                  : std::string(),
          implicit_json(s.implicit_start), creep_json(cfg, s), corrosion_json(cfg, s),
          acoustic_emission, shpb));
}

}  // namespace

RunSummary write_results(const io::ModelConfig& cfg, const RunView& view, Curve curve,
                         const DriverOutcome& outcome, const measure::AeSettings& ae,
                         double wall_seconds, const std::filesystem::path& out) {
  const model::Model& model = view.model;
  const solver::Solver& solver = view.solver;
  const geometry::Tessellation& specimen = view.specimen;
  RunSummary summary;
  summary.exit_code = outcome.exit_code;
  summary.status = outcome.status;
  summary.implicit_start = outcome.implicit_start;
  summary.creep = outcome.creep;
  summary.corrosion = outcome.corrosion;
  summary.blocks = model.blocks.size();
  const double peak = outcome.peak, trough = outcome.trough;
  // A pulled specimen (direct tension): its elastic constants come from the tensile branch.
  const double sense = -trough > peak ? -1.0 : 1.0;
  for (auto* h : {&curve.strain, &curve.stress, &curve.lateral})
    for (double& x : *h) x *= sense;
  const bool brazilian =
      cfg.tessellation.outline.kind == geometry::OutlineKind::disc && !cfg.specimen_file;
  // A disc's platen stress and strain define no Young's modulus: none is reported.
  const auto ec = brazilian ? measure::ElasticConstants{}
                            : measure::elastic_constants(curve.strain, curve.stress, curve.lateral);
  summary.peak_stress = peak;
  // Brazilian test (disc between platens): sigma_t = 2 F / (pi D t), and the axial stress is
  // F / (D t); on flats subtending 2 alpha, times (sin 2 alpha - alpha) / alpha, the centre's
  // stress under a load spread over that arc (Hondros 1959). Direct tension: the largest pull.
  const double a = cfg.tessellation.outline.flat_angle / 2;
  const double spread = a > 0 ? (std::sin(2 * a) - a) / a : 1.0;
  if (brazilian)
    summary.tensile_strength = 2.0 / M_PI * peak * spread;
  else if (trough < 0)
    summary.tensile_strength = -trough;
  summary.failure_stages = measure::failure_stages(curve.strain, curve.stress, curve.failure_rate);
  summary.cycles = measure::cycle_measures(curve.rows, cfg.load_path.stages, outcome.stalled);
  if (!summary.cycles.empty()) write_cycles(out / "cycles.csv", summary.cycles);
  summary.youngs_modulus = ec.youngs_modulus;
  summary.zones = model.zoning.zones.size();
  if (!model.zoning.empty()) {
    const model::ZoneStress m = model::mean_stress(model, model::Group::specimen);
    summary.zone_stress_xx = -m.xx;
    summary.zone_stress_yy = -m.yy;
    summary.zone_stress_xy = -m.xy;
  }
  summary.poisson_ratio = ec.poisson_ratio;
  summary.initial_poisson_ratio = ec.initial_poisson_ratio;
  summary.steps = solver.steps();
  summary.contacts = model.contacts.size();
  for (const auto& e : solver.cracks())
    (e.type == laws::ContactEvent::tensile_failure ? summary.cracks_tensile
                                                   : summary.cracks_shear)++;
  summary.wall_seconds = wall_seconds;
  if (view.bars) write_fragments(model, out);
  write_summary(
      out / "summary.json", cfg, summary, solver.initial_bonded_contacts(), solver.dt(),
      summary.cracks_tensile + summary.cracks_shear,
      grain_summary(cfg, specimen, measure::grain_cracks(solver.cracks(), specimen.block_grain)),
      ae_json(measure::cluster_events(solver.cracks(), ae), ae),
      view.bars ? shpb_json(*view.bars, solver, model) : std::string());
  return summary;
}

}  // namespace vorodec::app
