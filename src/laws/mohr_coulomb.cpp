#include "vorodec/laws/mohr_coulomb.hpp"

#include <numbers>

#include "vorodec/laws/law_group.hpp"

namespace vorodec::laws {

namespace {
// Random stream of each property (fixed: a contact's draws must not change between versions).
enum Property : std::uint32_t {
  jkn,
  jks,
  tension,
  cohesion,
  friction,
  dilation,
  residual_friction
};
}  // namespace

MohrCoulomb::Params MohrCoulomb::params_from(const LawParams& p) {
  return {p.at("jkn"), p.at("jks"), coulomb_params_from(p), p.at("dilation")};
}

MohrCoulomb::Props MohrCoulomb::sample(const Params& p, std::uint64_t seed, const NewContact& c) {
  return {p.jkn.sample(seed, c.id, jkn) * c.length, p.jks.sample(seed, c.id, jks) * c.length,
          sample_strength(p.strength, seed, c, {tension, cohesion, friction, residual_friction}),
          std::tan(p.dilation.sample(seed, c.id, dilation) * std::numbers::pi / 180.0)};
}

namespace {
constexpr ParamSpec mohr_coulomb_params[] = {
    {"jkn", "Pa/m", "joint normal stiffness per unit contact length", 0, false, no_limit, required,
     true, false},
    {"jks", "Pa/m", "joint shear stiffness per unit contact length", 0, true, no_limit, required,
     true, false},
    tension_spec,
    cohesion_spec,
    friction_spec,
    {"dilation", "deg", "dilation angle, active while a failed joint slips", 0, true, 89.9, 0.0,
     true, false},
    residual_friction_spec,
};
}  // namespace

extern const LawInfo mohr_coulomb_info;
const LawInfo mohr_coulomb_info{
    MohrCoulomb::name,
    "Coulomb slip with tension cut-off, cohesion, dilation and residual friction",
    mohr_coulomb_params,
    [](const LawParams& p, std::uint64_t seed) -> std::unique_ptr<LawGroup> {
      return std::make_unique<LawGroupOf<MohrCoulomb>>(p, seed);
    },
    [](const LawParams& p) {
      return NominalStiffness{mean_of(p, "jkn"), mean_of(p, "jks")};
    }};

}  // namespace vorodec::laws
