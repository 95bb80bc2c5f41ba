#pragma once
// Per-contact property values: a constant or a Weibull distribution, sampled from a counter-based
// stream keyed by (seed, contact id, property) so values do not depend on ordering or threads.
#include <cstdint>

namespace vorodec::model {

struct Distribution {
  double value = 0.0;          // the constant value, or the distribution's mean
  double weibull_shape = 0.0;  // m; 0 = constant
  double weibull_scale = 0.0;  // lambda = mean / Gamma(1 + 1/m)

  static Distribution constant(double v) { return {v, 0.0, 0.0}; }
  static Distribution weibull_from_mean(double shape, double mean);
  static Distribution weibull_from_scale(double shape, double scale);

  bool is_constant() const { return weibull_shape == 0.0; }
  double mean() const { return value; }
  double sample(std::uint64_t seed, std::uint64_t contact_id, std::uint32_t property) const;
};

// Uniform variate in (0, 1), a pure function of its key (SplitMix64 finaliser).
double keyed_uniform(std::uint64_t seed, std::uint64_t contact_id, std::uint32_t property);

}  // namespace vorodec::model
