#pragma once
// The strength layer every bonded law shares (docs/theory.md §6.2): a tension cut-off and a Coulomb
// slider with cohesion, both lost at failure, then residual friction. A law computes its trial
// forces with its own elastic part and passes them through these checks.
#include <algorithm>
#include <cmath>
#include <limits>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::laws {

struct CoulombStrength {
  double tension_force;   // N, tensile strength x length
  double cohesion_force;  // N, cohesion x length
  double tan_phi, tan_phi_res;
};

// The layer's model-file keys, one row each for the laws' parameter tables.
inline constexpr double no_limit = 1e300;
inline constexpr ParamSpec tension_spec{
    "tension", "Pa", "tensile strength (lost at failure)", 0, true, no_limit, 0.0, true, false};
inline constexpr ParamSpec cohesion_spec{
    "cohesion", "Pa", "cohesion (lost at failure)", 0, true, no_limit, 0.0, true, false};
inline constexpr ParamSpec friction_spec{
    "friction", "deg", "friction angle", 0, true, 89.9, required, true, false};
inline constexpr ParamSpec residual_friction_spec{
    "residual_friction",
    "deg",
    "friction angle after failure (default: friction)",
    0,
    true,
    89.9,
    required,
    true,
    true};

struct CoulombParams {
  model::Distribution tension, cohesion, friction, residual_friction;
};
CoulombParams coulomb_params_from(const LawParams& p);
// Which random stream of a contact each property draws from (a law's own numbering).
struct CoulombStreams {
  std::uint32_t tension, cohesion, friction, residual_friction;
};
CoulombStrength sample_strength(const CoulombParams& p, std::uint64_t seed, const NewContact& c,
                                CoulombStreams streams);

// Tension cut-off on the trial normal force r.fn (compression positive): below -tension (zero
// once broken) the joint opens, carries no force, and is broken from then on. True if it opened.
[[gnu::always_inline]] inline bool opens_in_tension(const CoulombStrength& p, bool& broken,
                                                    LawResult& r) {
  if (r.fn < -(broken ? 0.0 : p.tension_force)) {
    if (!broken) r.event = ContactEvent::tensile_failure;
    broken = true;
    r.elastic = false;
    r.fn = 0.0;
    return true;
  }
  return false;
}

// Coulomb slider on the trial shear force under normal force r.fn: |fs| <= c + fn tan(phi)
// while intact, fn tan(phi_res) once broken. Returns the shear force the joint carries; a capped
// force marks the step slip or shear failure.
[[gnu::always_inline]] inline double cap_shear(const CoulombStrength& p, bool& broken, LawResult& r,
                                               double fs_trial) {
  double fmax = broken ? r.fn * p.tan_phi_res : p.cohesion_force + r.fn * p.tan_phi;
  const double fs_size = std::abs(fs_trial);
  if (fs_size > fmax && fs_size > 0.0) {  // |Fs| > max(Fmax, 0), as two compares: no blend
    r.elastic = false;
    if (!broken) {
      r.event = ContactEvent::shear_failure;
      broken = true;
      fmax = r.fn * p.tan_phi_res;
    } else {
      r.event = ContactEvent::slip;
    }
    return std::copysign(std::max(fmax, 0.0), fs_trial);
  }
  return fs_trial;
}

// First factor s >= 0 at which forces (fn + s dfn, fs + s dfs) reach the tension cut-off or
// either side of the Coulomb envelope (residual once broken); infinity if never. A joint without
// shear stiffness (shear = false) has no envelope to reach.
inline double coulomb_reach(const CoulombStrength& p, bool broken, bool shear, double fn, double fs,
                            double dfn, double dfs) {
  const double tension = broken ? 0.0 : p.tension_force;
  const double c = broken ? 0.0 : p.cohesion_force;
  const double t = broken ? p.tan_phi_res : p.tan_phi;
  double reach = std::numeric_limits<double>::infinity();
  // Each limit as a + s b <= 0: crossed at s = -a / b when b > 0, at once if already past.
  const auto limit = [&](double a, double b) {
    if (b > 0.0)
      reach = std::min(reach, std::max(-a / b, 0.0));
    else if (a > 0.0)
      reach = 0.0;
  };
  limit(-(fn + tension), -dfn);
  if (shear) {
    limit(fs - c - fn * t, dfs - dfn * t);
    limit(-fs - c - fn * t, -dfs - dfn * t);
  }
  return reach;
}

}  // namespace vorodec::laws
