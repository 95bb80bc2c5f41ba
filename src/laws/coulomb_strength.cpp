#include "vorodec/laws/coulomb_strength.hpp"

#include <numbers>

namespace vorodec::laws {

namespace {
double tan_deg(double deg) {
  return std::tan(deg * std::numbers::pi / 180.0);
}
}  // namespace

CoulombParams coulomb_params_from(const LawParams& p) {
  const auto residual = p.find("residual_friction");
  return {p.at("tension"), p.at("cohesion"), p.at("friction"),
          residual != p.end() ? residual->second : p.at("friction")};
}

CoulombStrength sample_strength(const CoulombParams& p, std::uint64_t seed, const NewContact& c,
                                CoulombStreams streams) {
  return {p.tension.sample(seed, c.id, streams.tension) * c.length,
          p.cohesion.sample(seed, c.id, streams.cohesion) * c.length,
          tan_deg(p.friction.sample(seed, c.id, streams.friction)),
          tan_deg(p.residual_friction.sample(seed, c.id, streams.residual_friction))};
}

}  // namespace vorodec::laws
