#include "vorodec/laws/mohr_coulomb.hpp"

#include <numbers>

#include "vorodec/laws/law_group.hpp"

namespace vorodec::laws {

namespace {
enum Property : std::uint32_t {
  jkn,
  jks,
  tension,
  cohesion,
  friction,
  dilation,
  residual_friction
};
double tan_deg(double deg) {
  return std::tan(deg * std::numbers::pi / 180.0);
}
}  // namespace

MohrCoulomb::Params MohrCoulomb::params_from(const LawParams& p) {
  const auto residual = p.find("residual_friction");
  return {p.at("jkn"),
          p.at("jks"),
          p.at("tension"),
          p.at("cohesion"),
          p.at("friction"),
          p.at("dilation"),
          residual != p.end() ? residual->second : p.at("friction")};
}

MohrCoulomb::Props MohrCoulomb::sample(const Params& p, std::uint64_t seed, const NewContact& c) {
  const auto draw = [&](const model::Distribution& d, Property k) {
    return d.sample(seed, c.id, k);
  };
  return {
      draw(p.jkn, jkn) * c.length,         draw(p.jks, jks) * c.length,
      draw(p.tension, tension) * c.length, draw(p.cohesion, cohesion) * c.length,
      tan_deg(draw(p.friction, friction)), tan_deg(draw(p.residual_friction, residual_friction)),
      tan_deg(draw(p.dilation, dilation))};
}

namespace {
constexpr double big = 1e300;
constexpr ParamSpec mohr_coulomb_params[] = {
    {"jkn", "Pa/m", "joint normal stiffness per unit contact length", 0, false, big, required, true,
     false},
    {"jks", "Pa/m", "joint shear stiffness per unit contact length", 0, true, big, required, true,
     false},
    {"tension", "Pa", "tensile strength (lost at failure)", 0, true, big, 0.0, true, false},
    {"cohesion", "Pa", "cohesion (lost at failure)", 0, true, big, 0.0, true, false},
    {"friction", "deg", "friction angle", 0, true, 89.9, required, true, false},
    {"dilation", "deg", "dilation angle, active while a failed joint slips", 0, true, 89.9, 0.0,
     true, false},
    {"residual_friction", "deg", "friction angle after failure (default: friction)", 0, true, 89.9,
     required, true, true},
};
}  // namespace

extern const LawInfo mohr_coulomb_info;
const LawInfo mohr_coulomb_info{
    MohrCoulomb::name,
    "Coulomb slip with tension cut-off, cohesion, dilation and residual friction",
    mohr_coulomb_params, [](const LawParams& p, std::uint64_t seed) -> std::unique_ptr<LawGroup> {
      return std::make_unique<LawGroupOf<MohrCoulomb>>(p, seed);
    }};

}  // namespace vorodec::laws
