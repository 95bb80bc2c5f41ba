#include "vorodec/model/weibull.hpp"

#include <cmath>

namespace vorodec::model {

namespace {
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
}  // namespace

double keyed_uniform(std::uint64_t seed, std::uint64_t contact_id, std::uint32_t property) {
  const std::uint64_t h =
      mix(mix(mix(seed) ^ contact_id) ^ (std::uint64_t{property} << 32 | property));
  // 53 random bits, shifted by half a unit so the result is never 0 or 1.
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

Distribution Distribution::weibull_from_mean(double shape, double mean) {
  return {mean, shape, mean / std::tgamma(1.0 + 1.0 / shape)};
}

Distribution Distribution::weibull_from_scale(double shape, double scale) {
  return {scale * std::tgamma(1.0 + 1.0 / shape), shape, scale};
}

double Distribution::sample(std::uint64_t seed, std::uint64_t contact_id,
                            std::uint32_t property) const {
  if (is_constant()) return value;
  const double u = keyed_uniform(seed, contact_id, property);
  return weibull_scale * std::pow(-std::log1p(-u), 1.0 / weibull_shape);
}

}  // namespace vorodec::model
