#include "vorodec/laws/burgers.hpp"

#include "vorodec/laws/law_group.hpp"

namespace vorodec::laws {

namespace {
// Random stream of each property.
enum Property : std::uint32_t {
  kmn,
  cmn,
  kkn,
  ckn,
  kms,
  cms,
  kks,
  cks,
  tension,
  cohesion,
  friction,
  residual_friction
};
}  // namespace

Burgers::Params Burgers::params_from(const LawParams& p) {
  return {p.at("kmn"),
          p.at("cmn"),
          p.at("kkn"),
          p.at("ckn"),
          p.at("kms"),
          p.at("cms"),
          p.at("kks"),
          p.at("cks"),
          coulomb_params_from(p),
          p.at("carry_tension").value != 0.0};
}

Burgers::Props Burgers::sample(const Params& p, std::uint64_t seed, const NewContact& c) {
  const auto draw = [&](const model::Distribution& d, Property k) {
    return d.sample(seed, c.id, k) * c.length;
  };
  return {{draw(p.kmn, kmn), draw(p.cmn, cmn), draw(p.kkn, kkn), draw(p.ckn, ckn)},
          {draw(p.kms, kms), draw(p.cms, cms), draw(p.kks, kks), draw(p.cks, cks)},
          sample_strength(p.strength, seed, c, {tension, cohesion, friction, residual_friction}),
          p.carry_tension ? 1.0 : 0.0};
}

namespace {
constexpr ParamSpec burgers_params[] = {
    {"kmn", "Pa/m", "Maxwell spring, normal, per unit contact length", 0, false, no_limit, required,
     true, false},
    {"cmn", "Pa s/m", "Maxwell dashpot, normal, per unit contact length", 0, false, no_limit,
     required, true, false},
    {"kkn", "Pa/m", "Kelvin spring, normal, per unit contact length", 0, false, no_limit, required,
     true, false},
    {"ckn", "Pa s/m", "Kelvin dashpot, normal, per unit contact length", 0, false, no_limit,
     required, true, false},
    {"kms", "Pa/m", "Maxwell spring, shear, per unit contact length", 0, false, no_limit, required,
     true, false},
    {"cms", "Pa s/m", "Maxwell dashpot, shear, per unit contact length", 0, false, no_limit,
     required, true, false},
    {"kks", "Pa/m", "Kelvin spring, shear, per unit contact length", 0, false, no_limit, required,
     true, false},
    {"cks", "Pa s/m", "Kelvin dashpot, shear, per unit contact length", 0, false, no_limit,
     required, true, false},
    tension_spec,
    cohesion_spec,
    friction_spec,
    residual_friction_spec,
    {"carry_tension", "bool",
     "true: the contact carries tension without limit (no tension cut-off, PFC's mode 0); "
     "false: the tension cut-off of the strength keys",
     0, true, 1, 0.0, false, false},
};
}  // namespace

extern const LawInfo burgers_info;
const LawInfo burgers_info{
    Burgers::name,
    "Burger's creep (Kelvin + Maxwell in series, normal and shear) with the Mohr-Coulomb "
    "strength layer",
    burgers_params,
    [](const LawParams& p, std::uint64_t seed) -> std::unique_ptr<LawGroup> {
      return std::make_unique<LawGroupOf<Burgers>>(p, seed);
    },
    [](const LawParams& p) {
      return NominalStiffness{mean_of(p, "kmn"), mean_of(p, "kms")};
    }};

}  // namespace vorodec::laws
