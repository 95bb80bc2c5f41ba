#include "vorodec/laws/barton_bandis.hpp"

#include "vorodec/laws/coulomb_strength.hpp"
#include "vorodec/laws/law_group.hpp"

namespace vorodec::laws {

namespace {
// Random stream of each property (fixed: a contact's draws must not change between versions).
enum Property : std::uint32_t { jkn, max_closure, jks, jrc, jcs, residual_friction, sn_max };
}  // namespace

BartonBandis::Params BartonBandis::params_from(const LawParams& p) {
  const auto limit = p.find("max_normal_stress");
  return {p.at("jkn"),
          p.at("max_closure"),
          p.at("jks"),
          p.at("jrc"),
          p.at("jcs"),
          p.at("residual_friction"),
          limit != p.end() ? limit->second : model::Distribution::constant(0.0)};
}

BartonBandis::Props BartonBandis::sample(const Params& p, std::uint64_t seed, const NewContact& c) {
  const double jcs_value = p.jcs.sample(seed, c.id, jcs);
  const double limit =
      p.max_normal_stress.value > 0.0 ? p.max_normal_stress.sample(seed, c.id, sn_max) : jcs_value;
  return {p.jkn.sample(seed, c.id, jkn),
          p.max_closure.sample(seed, c.id, max_closure),
          p.jks.sample(seed, c.id, jks),
          p.jrc.sample(seed, c.id, jrc),
          jcs_value,
          p.residual_friction.sample(seed, c.id, residual_friction),
          limit,
          c.length};
}

namespace {
constexpr ParamSpec barton_bandis_params[] = {
    {"jkn", "Pa/m",
     "initial normal stiffness kni of the hyperbolic closure, per unit contact length", 0, false,
     no_limit, required, true, false},
    {"max_closure", "m", "maximum closure vm of the hyperbola sn = kni v / (1 - v / vm)", 0, false,
     no_limit, required, true, false},
    {"jks", "Pa/m", "joint shear stiffness per unit contact length (elastic up to the peak)", 0,
     false, no_limit, required, true, false},
    {"jrc", "-", "joint roughness coefficient JRC (0-20 for Barton's profiles)", 0, true, 40,
     required, true, false},
    {"jcs", "Pa", "joint wall compressive strength JCS", 0, false, no_limit, required, true, false},
    {"residual_friction", "deg", "residual friction angle phi_r", 0, true, 89.9, required, true,
     false},
    {"max_normal_stress", "Pa",
     "where the hyperbola ends: linear beyond, with its tangent stiffness there, which sets the "
     "time step (default: jcs)",
     0, false, no_limit, required, true, true},
};
}  // namespace

extern const LawInfo barton_bandis_info;
const LawInfo barton_bandis_info{
    BartonBandis::name,
    "Rough rock joint: Bandis hyperbolic closure, Barton-Choubey peak strength, mobilised-JRC "
    "softening and dilation, no tension",
    barton_bandis_params,
    [](const LawParams& p, std::uint64_t seed) -> std::unique_ptr<LawGroup> {
      return std::make_unique<LawGroupOf<BartonBandis>>(p, seed);
    },
    [](const LawParams& p) {
      return NominalStiffness{mean_of(p, "jkn"), mean_of(p, "jks")};
    }};

}  // namespace vorodec::laws
