#include "vorodec/measure/three_wave.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vorodec::measure {

std::vector<ThreeWavePoint> three_wave(const BarPair& bars, std::span<const double> t,
                                       std::span<const double> eps_i, std::span<const double> eps_r,
                                       std::span<const double> eps_t) {
  std::vector<ThreeWavePoint> out;
  out.reserve(t.size());
  const Bar1D &in = bars.incident, &tr = bars.transmitted;
  const double as = bars.specimen_width;
  for (std::size_t k = 0; k < t.size(); ++k) {
    ThreeWavePoint p{};
    p.t = t[k];
    p.eps_i = eps_i[k];
    p.eps_r = eps_r[k];
    p.eps_t = eps_t[k];
    p.s1 = in.youngs_modulus * in.width * (p.eps_i + p.eps_r) / as;
    p.s2 = tr.youngs_modulus * tr.width * p.eps_t / as;
    p.stress = 0.5 * (p.s1 + p.s2);
    p.strain_rate =
        (in.wave_speed * (p.eps_i - p.eps_r) - tr.wave_speed * p.eps_t) / bars.specimen_length;
    p.strain = k == 0 ? 0.0
                      : out.back().strain +
                            0.5 * (out.back().strain_rate + p.strain_rate) * (p.t - out.back().t);
    const double sum = p.s1 + p.s2;
    p.eta = sum != 0.0 ? 2.0 * (p.s1 - p.s2) / sum : std::numeric_limits<double>::quiet_NaN();
    out.push_back(p);
  }
  return out;
}

PulseShape pulse_shape(std::span<const double> t, std::span<const double> stress) {
  PulseShape p;
  p.peak = stress.empty() ? 0.0 : *std::max_element(stress.begin(), stress.end());
  double up = NAN, down = NAN;
  for (std::size_t k = 1; k < stress.size(); ++k) {
    const double a = stress[k - 1] - 0.5 * p.peak, b = stress[k] - 0.5 * p.peak;
    const double at = t[k - 1] + (t[k] - t[k - 1]) * a / (a - b);
    if (a < 0 && b >= 0 && std::isnan(up)) up = at;
    if (a >= 0 && b < 0 && !std::isnan(up) && std::isnan(down)) down = at;
  }
  p.duration = down - up;
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < stress.size(); ++k)
    if (std::abs(t[k] - 0.5 * (up + down)) <= 0.25 * p.duration) {
      sum += stress[k];
      ++n;
    }
  p.plateau = n ? sum / static_cast<double>(n) : NAN;
  return p;
}

DynamicMeasures dynamic_measures(const BarPair& bars, std::span<const ThreeWavePoint> points,
                                 double equilibrium_tolerance) {
  DynamicMeasures m;
  m.equilibrium_tolerance = equilibrium_tolerance;
  // Energy flux through a bar's section: A sigma^2 / (rho c0) = A E c0 eps^2 (per m thickness).
  const Bar1D &in = bars.incident, &tr = bars.transmitted;
  const double f_in = in.youngs_modulus * in.wave_speed * in.width;
  const double f_tr = tr.youngs_modulus * tr.wave_speed * tr.width;
  for (std::size_t k = 1; k < points.size(); ++k) {
    const ThreeWavePoint &a = points[k - 1], &b = points[k];
    const double h = 0.5 * (b.t - a.t);
    m.incident_energy += h * f_in * (a.eps_i * a.eps_i + b.eps_i * b.eps_i);
    m.reflected_energy += h * f_in * (a.eps_r * a.eps_r + b.eps_r * b.eps_r);
    m.transmitted_energy += h * f_tr * (a.eps_t * a.eps_t + b.eps_t * b.eps_t);
  }
  const auto peak = std::max_element(
      points.begin(), points.end(),
      [](const ThreeWavePoint& a, const ThreeWavePoint& b) { return a.stress < b.stress; });
  if (peak == points.end() || peak->stress <= 0.0) return m;
  m.valid = true;
  m.peak_stress = peak->stress;
  m.peak_time = peak->t;
  m.strain_at_peak = peak->strain;
  m.strain_rate_at_peak = peak->strain_rate;
  m.eta_at_peak = peak->eta;
  m.mean_strain_rate = m.peak_time > 0 ? m.strain_at_peak / m.peak_time : 0.0;
  const auto end = peak + 1;
  m.equilibrium_time = std::numeric_limits<double>::quiet_NaN();
  for (auto p = points.begin(); p != end; ++p) {
    if (!(std::abs(p->eta) <= equilibrium_tolerance))
      m.equilibrium_time = std::numeric_limits<double>::quiet_NaN();
    else if (std::isnan(m.equilibrium_time))
      m.equilibrium_time = p->t;
    if (p->stress >= 0.5 * m.peak_stress) m.eta_loading = std::max(m.eta_loading, std::abs(p->eta));
  }
  const auto arrival = std::find_if(
      points.begin(), end, [&](const ThreeWavePoint& p) { return p.s2 > 0.01 * m.peak_stress; });
  m.ring_up_time = arrival != end ? 3.0 * (arrival->t - points.front().t)
                                  : std::numeric_limits<double>::quiet_NaN();
  m.eta_after_ring_up = std::numeric_limits<double>::quiet_NaN();
  for (auto p = points.begin(); p != end; ++p)
    if (p->t - points.front().t >= m.ring_up_time)
      m.eta_after_ring_up = std::isnan(m.eta_after_ring_up)
                                ? std::abs(p->eta)
                                : std::max(m.eta_after_ring_up, std::abs(p->eta));
  return m;
}

}  // namespace vorodec::measure
