#include "vorodec/measure/failure_stages.hpp"

#include <algorithm>

namespace vorodec::measure {

FailureStages failure_stages(std::span<const double> strain, std::span<const double> stress,
                             std::span<const double> rate) {
  FailureStages f;
  if (stress.empty()) return f;
  const auto ip =
      static_cast<std::size_t>(std::max_element(stress.begin(), stress.end()) - stress.begin());
  const auto first = std::find_if(rate.begin(), rate.begin() + static_cast<long>(ip) + 1,
                                  [](double r) { return r > 0; });
  const auto i0 = static_cast<std::size_t>(first - rate.begin());
  if (i0 > ip || ip < 2) return f;
  f.crack_initiation_stress = stress[i0];
  f.peak_stress = stress[ip];
  f.accelerating_stress = stress[ip];
  const std::size_t w = std::max<std::size_t>(1, (ip - i0) / 20);
  for (std::size_t i = i0 + 2 * w; i <= ip; ++i) {
    const double de_local = strain[i] - strain[i - w], de_mean = strain[i] - strain[i0];
    if (de_local <= 0 || de_mean <= 0) continue;
    const double local = (rate[i] - rate[i - w]) / de_local;
    const double mean = (rate[i] - rate[i0]) / de_mean;
    if (mean > 0 && local > 2.0 * mean) {
      f.accelerating_stress = stress[i];
      break;
    }
  }
  f.valid = true;
  return f;
}

}  // namespace vorodec::measure
