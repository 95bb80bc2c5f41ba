#include "vorodec/outputs/results.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "shpb_output.hpp"
#include "vorodec/io/atomic_file.hpp"
#include "vorodec/io/csv_writer.hpp"
#include "vorodec/io/json.hpp"
#include "vorodec/measure/failure_stages.hpp"
#include "vorodec/measure/grain_cracks.hpp"
#include "vorodec/measure/specimen.hpp"
#include "vorodec/outputs/ae_output.hpp"

namespace vorodec::run {

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
void add_grains(io::Json& json, const io::ModelConfig& cfg, const geometry::Tessellation& tess,
                const measure::GrainCracks& g) {
  if (!cfg.grains) return;
  double total = 0;
  for (const double a : tess.mineral_area) total += a;
  io::Json minerals = io::Json::object();
  for (std::size_t m = 0; m < cfg.grains->minerals.size(); ++m)
    minerals[cfg.grains->minerals[m].name] = {
        {"requested", io::rounded(cfg.grains->minerals[m].fraction, 6)},
        {"achieved",
         io::rounded(m < tess.mineral_area.size() ? tess.mineral_area[m] / total : 0.0, 6)}};
  io::Json cracks = io::Json::object();
  for (std::size_t k = 0; k < measure::kCrackClasses; ++k)
    cracks[std::string(measure::kCrackClassNames[k])] = {{"count", g.count[k]},
                                                         {"length_m", io::rounded(g.length[k], 6)}};
  json["grains"] = tess.grain_mineral.size();
  json["mineral_area_fractions"] = std::move(minerals);
  json["crack_classes"] = std::move(cracks);
}

io::Json summary_json(const io::ModelConfig& cfg, const RunSummary& s) {
  const auto& f = s.failure_stages;
  io::Json j;
  j["model"] = cfg.file.filename().string();
  j["title"] = cfg.title;
  j["status"] = s.status;
  j["peak_stress_Pa"] = io::rounded(s.peak_stress, 8);
  j["peak_passed"] = s.peak_passed;
  j["tensile_strength_Pa"] = io::rounded(s.tensile_strength, 8);
  j["failure_stages"] = nullptr;
  if (f.valid)
    j["failure_stages"] = {
        {"crack_initiation_stress_Pa", io::rounded(f.crack_initiation_stress, 8)},
        {"accelerating_crack_growth_stress_Pa", io::rounded(f.accelerating_stress, 8)},
        {"peak_stress_Pa", io::rounded(f.peak_stress, 8)}};
  j["cycles"] = s.cycles.size();
  j["youngs_modulus_Pa"] = io::rounded(s.youngs_modulus, 8);
  j["poisson_ratio"] = io::rounded(s.poisson_ratio, 6);
  j["initial_poisson_ratio"] = io::rounded(s.initial_poisson_ratio, 6);
  j["elastic_fit"] =
      "tangent over 40-60 % of peak (initial: 10-30 %), plane-strain apparent values";
  j["cracks"] = {{"tensile", s.cracks_tensile}, {"shear", s.cracks_shear}};
  return j;
}

void add_counts(io::Json& j, const RunSummary& s, std::size_t initial_contacts, double dt,
                std::size_t broken) {
  j["failure_rate"] =
      io::rounded(initial_contacts ? double(broken) / double(initial_contacts) : 0.0, 6);
  j["blocks"] = s.blocks;
  j["initial_contacts"] = initial_contacts;
  j["time_step_s"] = io::rounded(dt, 6);
  j["steps"] = s.steps;
  j["wall_time_s"] = io::fixed(s.wall_seconds, 3);
  if (s.zones) {
    j["zones"] = s.zones;
    j["zone_stress_Pa"] = {{"xx", io::rounded(s.zone_stress_xx, 8)},
                           {"yy", io::rounded(s.zone_stress_yy, 8)},
                           {"xy", io::rounded(s.zone_stress_xy, 8)}};
  }
}

}  // namespace

RunSummary write_results(const io::ModelConfig& cfg, const Driver& driver, Curve curve,
                         const measure::AeSettings& ae, double wall_seconds,
                         const std::filesystem::path& out) {
  const RunView view = driver.view();
  const DriverOutcome& outcome = driver.outcome();
  const model::Model& model = view.model;
  const solver::Solver& solver = view.solver;
  const geometry::Tessellation& specimen = view.specimen;
  RunSummary summary;
  summary.exit_code = outcome.exit_code;
  summary.status = outcome.status;
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
  const auto top = std::max_element(curve.stress.begin(), curve.stress.end());
  summary.peak_passed =
      top != curve.stress.end() &&
      std::any_of(top, curve.stress.end(), [&](double s) { return s < 0.99 * *top; });
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
  io::Json json = summary_json(cfg, summary);
  add_grains(json, cfg, specimen, measure::grain_cracks(solver.cracks(), specimen.block_grain));
  add_counts(json, summary, solver.initial_bonded_contacts(), solver.dt(),
             summary.cracks_tensile + summary.cracks_shear);
  driver.summarise(json);
  json["acoustic_emission"] = ae_json(measure::cluster_events(solver.cracks(), ae), ae);
  if (view.bars) json["shpb"] = shpb_json(*view.bars, solver, model);
  io::write_json_atomically(out / "summary.json", json);
  return summary;
}

}  // namespace vorodec::run
