#include "vorodec/loading/pressure_bar.hpp"

#include <algorithm>

namespace vorodec::loading {

void WaveHistory::add(double t, double sigma) {
  t_.push_back(t);
  s_.push_back(sigma);
}

double WaveHistory::at(double t) const {
  if (t_.empty() || t < t_.front()) return 0.0;
  if (t >= t_.back()) return s_.back();
  const auto i = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin());
  const double w = (t - t_[i - 1]) / (t_[i] - t_[i - 1]);
  return (1.0 - w) * s_[i - 1] + w * s_[i];
}

ElasticBar::ElasticBar(BarProperties p, std::function<double(double)> source)
    : p_(p), source_(std::move(source)), c_(p.wave_speed()), z_(p.impedance()) {}

double ElasticBar::far_emitted(double t) const {
  const double own = source_ ? source_(t) : 0.0;
  if (p_.quiet_far_end) return own;
  return own - emitted_.at(t - p_.length / c_);  // a free end reflects with the opposite sign
}

std::function<double(double)> striker_pulse(const BarProperties& bar, double ls, double v,
                                            double t0, double rise, bool smooth) {
  const double sigma = 0.5 * bar.impedance() * v, duration = 2.0 * ls / bar.wave_speed();
  return [=](double t) {
    const double u = t - t0;
    if (u < 0.0 || u >= duration) return 0.0;
    if (rise <= 0.0) return sigma;
    const double ramp = std::min({1.0, u / rise, (duration - u) / rise});
    return smooth ? sigma * 0.5 * (1.0 - std::cos(M_PI * ramp)) : sigma * ramp;
  };
}

}  // namespace vorodec::loading
