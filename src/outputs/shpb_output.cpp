#include "shpb_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "vorodec/io/atomic_file.hpp"
#include "vorodec/io/json.hpp"
#include "vorodec/loading/pressure_bar.hpp"
#include "vorodec/measure/fragments.hpp"

namespace vorodec::run {

namespace {

measure::Bar1D bar1d(const loading::BarProperties& p) {
  return {p.wave_speed(), p.youngs_modulus, p.width};
}

measure::BarPair pair_of(const BarsView& b) {
  return {bar1d(b.cfg.incident), bar1d(b.cfg.transmitted), b.specimen_width, b.specimen_length};
}

// Strain at x m from the face at t s.
double gauge(const std::function<double(double, double)>& bar, const loading::BarProperties& p,
             double x, double t) {
  return bar(x, t) / p.youngs_modulus;
}

}  // namespace

double analysis_window(const BarsView& b) {
  const loading::BarProperties &in = b.cfg.incident, &tr = b.cfg.transmitted;
  const double di = b.cfg.incident_gauges.front(), dt = b.cfg.transmitted_gauges.front();
  double end = std::min(b.cfg.duration, 2.0 * di / in.wave_speed());
  if (!in.quiet_far_end) end = std::min(end, 2.0 * (in.length - di) / in.wave_speed());
  if (!tr.quiet_far_end) end = std::min(end, 2.0 * (tr.length - dt) / tr.wave_speed());
  // A run that stopped early (unstable, --max-steps) has no faces' record beyond its end.
  return std::min(end, b.recorded_until - b.reach);
}

std::vector<measure::ThreeWavePoint> analyse(const BarsView& b) {
  const double di = b.cfg.incident_gauges.front(), dt = b.cfg.transmitted_gauges.front();
  const double ci = b.cfg.incident.wave_speed(), ct = b.cfg.transmitted.wave_speed();
  const double end = analysis_window(b), h = b.cfg.record_interval;
  std::vector<double> t, ei, er, et;
  for (long k = 0; k * h <= end; ++k) {
    const double tk = static_cast<double>(k) * h;
    t.push_back(tk);
    ei.push_back(gauge(b.incident, b.cfg.incident, di, tk - di / ci));
    er.push_back(gauge(b.incident, b.cfg.incident, di, tk + di / ci));
    et.push_back(gauge(b.transmitted, b.cfg.transmitted, dt, tk + dt / ct));
  }
  return measure::three_wave(pair_of(b), t, ei, er, et);
}

// The incident pulse as the first incident gauge saw it, before its reflection comes back (the
// model file keeps every incident gauge at least half the pulse from the face).
measure::PulseShape incident_pulse(const BarsView& b) {
  const loading::BarProperties& in = b.cfg.incident;
  const double x = b.cfg.incident_gauges.front(), c = in.wave_speed(), h = b.cfg.record_interval;
  const double pulse = 2.0 * b.cfg.striker_length / c;
  const double begin = std::max(-in.length / c, -x / c - 0.1 * pulse);
  const double end = std::min(-x / c + 1.1 * pulse, x / c);
  std::vector<double> t, s;
  for (long k = 0; begin + static_cast<double>(k) * h <= end; ++k) {
    t.push_back(begin + static_cast<double>(k) * h);
    s.push_back(b.incident(x, t.back()));
  }
  return measure::pulse_shape(t, s);
}

void write_bars(const BarsView& b, const std::filesystem::path& out) {
  const auto& cfg = b.cfg;
  const double ci = cfg.incident.wave_speed(), ct = cfg.transmitted.wave_speed();
  const double reach = std::max(
      *std::max_element(cfg.incident_gauges.begin(), cfg.incident_gauges.end()) / ci,
      *std::max_element(cfg.transmitted_gauges.begin(), cfg.transmitted_gauges.end()) / ct);
  std::string g = "time";
  for (const double x : cfg.incident_gauges) g += fmt::format(",incident_{:.6g}m", x);
  for (const double x : cfg.transmitted_gauges) g += fmt::format(",transmitted_{:.6g}m", x);
  g += '\n';
  const double h = cfg.record_interval;
  for (long k = static_cast<long>(std::floor(-reach / h)); k * h <= cfg.duration + reach; ++k) {
    const double t = static_cast<double>(k) * h;
    g += fmt::format("{:.9g}", t);
    for (const double x : cfg.incident_gauges)
      g += fmt::format(",{:.9g}", gauge(b.incident, cfg.incident, x, t));
    for (const double x : cfg.transmitted_gauges)
      g += fmt::format(",{:.9g}", gauge(b.transmitted, cfg.transmitted, x, t));
    g += '\n';
  }
  io::write_file_atomically(out / "gauges.csv", g);

  std::string s =
      "time,eps_incident,eps_reflected,eps_transmitted,stress_incident_face,"
      "stress_transmitted_face,stress,strain_rate,strain,eta,face_force_stress\n";
  const double ai = cfg.incident.width / b.specimen_width;
  const double at = cfg.transmitted.width / b.specimen_width;
  for (const measure::ThreeWavePoint& p : analyse(b)) {
    // The specimen's stress straight from the face forces the bars recorded (mean of the two).
    const double direct = 0.5 * (ai * b.incident(0.0, p.t) + at * b.transmitted(0.0, p.t));
    s += fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{:.9g}\n",
                     p.t, p.eps_i, p.eps_r, p.eps_t, p.s1, p.s2, p.stress, p.strain_rate, p.strain,
                     std::isfinite(p.eta) ? fmt::format("{:.6g}", p.eta) : std::string("nan"),
                     direct);
  }
  io::write_file_atomically(out / "bars.csv", s);
}

void write_fragments(const model::Model& model, const std::filesystem::path& out) {
  std::string csv = "area,equivalent_diameter\n";
  for (const double a : measure::fragment_areas(model))
    csv += fmt::format("{:.9g},{:.9g}\n", a, std::sqrt(4.0 * a / M_PI));
  io::write_file_atomically(out / "fragments.csv", csv);
}

io::Json shpb_json(const BarsView& b, const solver::Solver& solver, const model::Model& model) {
  const auto& cfg = b.cfg;
  const std::vector<measure::ThreeWavePoint> points = analyse(b);
  const measure::DynamicMeasures m =
      measure::dynamic_measures(pair_of(b), points, cfg.equilibrium_tolerance);
  // The specimen's stress straight from the face forces: its largest over the record.
  double peak_direct = 0;
  for (long k = 0; k * cfg.record_interval <= b.recorded_until; ++k) {
    const double t = static_cast<double>(k) * cfg.record_interval;
    peak_direct = std::max(peak_direct, 0.5 *
                                            (cfg.incident.width * b.incident(0.0, t) +
                                             cfg.transmitted.width * b.transmitted(0.0, t)) /
                                            b.specimen_width);
  }
  const measure::PulseShape pulse = incident_pulse(b);
  const double w_in = m.incident_energy, w_ref = m.reflected_energy, w_tr = m.transmitted_energy;
  const solver::Energy& e = solver.energy();
  const std::vector<double> fragments = measure::fragment_areas(model);
  double specimen_area = 0;
  for (const double a : fragments) specimen_area += a;
  io::Json sizes = io::Json::array();
  for (std::size_t k = 0; k < std::min<std::size_t>(fragments.size(), 20); ++k)
    sizes.push_back(io::rounded(fragments[k] / specimen_area, 6));
  const auto measured = [&](double v) { return m.valid ? io::rounded(v, 8) : io::Json(nullptr); };
  return {
      {"bars", cfg.block_bars ? "blocks" : "exact"},
      {"striker_velocity_m_per_s", io::rounded(cfg.striker_velocity, 6)},
      {"striker_length_m", io::rounded(cfg.striker_length, 6)},
      {"incident_stress_Pa", io::rounded(0.5 * cfg.incident.impedance() * cfg.striker_velocity, 8)},
      {"pulse_duration_s", io::rounded(2.0 * cfg.striker_length / cfg.incident.wave_speed(), 6)},
      {"measured_incident_stress_Pa", io::rounded(pulse.plateau, 8)},
      {"measured_pulse_duration_s", io::rounded(pulse.duration, 8)},
      {"analysis_window_s", io::rounded(analysis_window(b), 6)},
      {"dynamic_strength_Pa", measured(m.peak_stress)},
      {"peak_time_s", measured(m.peak_time)},
      {"strain_at_peak", measured(m.strain_at_peak)},
      {"strain_rate_at_peak_per_s", measured(m.strain_rate_at_peak)},
      {"mean_strain_rate_per_s", measured(m.mean_strain_rate)},
      {"peak_face_force_stress_Pa", io::rounded(peak_direct, 8)},
      {"eta_at_peak", measured(m.eta_at_peak)},
      {"eta_loading_max", io::rounded(m.eta_loading, 8)},
      {"ring_up_time_s", io::rounded(m.ring_up_time, 8)},
      {"eta_after_ring_up_max", io::rounded(m.eta_after_ring_up, 8)},
      {"equilibrium_tolerance", io::rounded(cfg.equilibrium_tolerance, 4)},
      {"equilibrium_time_s", io::rounded(m.equilibrium_time, 8)},
      {"energy_J_per_m",
       {{"incident", io::rounded(w_in, 8)},
        {"reflected", io::rounded(w_ref, 8)},
        {"transmitted", io::rounded(w_tr, 8)},
        {"absorbed", io::rounded(w_in - w_ref - w_tr, 8)},
        {"boundary_work", io::rounded(e.boundary_work, 8)},
        {"breakage", io::rounded(e.breakage, 8)},
        {"friction", io::rounded(e.slip, 8)},
        {"damping", io::rounded(e.damping, 8)},
        {"kinetic", io::rounded(solver.kinetic_energy(), 8)},
        {"strain", io::rounded(solver.contact_strain_energy() + solver.zone_strain_energy(), 8)}}},
      {"fragments", fragments.size()},
      {"largest_fragments_area_fraction", std::move(sizes)}};
}

}  // namespace vorodec::run
