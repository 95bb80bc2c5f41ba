#pragma once
// Coulomb slip joint with tension cut-off, cohesion, dilation and residual strength
// (PHYSICS section 4; UDEC "Coulomb slip with residual strength", 3DEC Mohr-Coulomb joint).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::laws {

struct MohrCoulomb {
  static constexpr std::string_view name = "mohr_coulomb";

  struct Params {
    model::Distribution jkn, jks, tension, cohesion, friction, dilation, residual_friction;
  };
  // Sampled per contact, already multiplied by the contact length where the law needs forces.
  struct Props {
    double kn, ks;          // N/m
    double tension_force;   // N, tensile strength x length
    double cohesion_force;  // N, cohesion x length
    double tan_phi, tan_phi_res, tan_psi;
  };
  static constexpr std::array<std::string_view, 7> property_names{
      "kn [N/m]",    "ks [N/m]", "tension_force [N]", "cohesion_force [N]", "tan_phi",
      "tan_phi_res", "tan_psi"};
  struct State {
    double fs;     // N, shear force carried into the next step
    double u_dil;  // m, gap at which the normal spring is unloaded: NewContact::spring_origin +
                   // dilation
    bool broken;   // tension and cohesion lost, residual friction applies
  };

  static Params params_from(const LawParams& p);
  static Props sample(const Params& p, std::uint64_t seed, const NewContact& c);
  static State initial_state(const NewContact& c) { return {0.0, c.spring_origin, !c.bonded}; }
  static double max_stiffness(const Props& p) { return std::max(p.kn, p.ks); }
  static double strain_energy(const Props& p, double fn, double fs) {
    return 0.5 * (fn * fn / p.kn + (p.ks > 0.0 ? fs * fs / p.ks : 0.0));
  }

  // A failed joint has no tension; while intact it has its tensile strength.
  static LinearSprings linear_springs(const Props& p, const State& st) {
    return {p.kn, p.ks, st.broken};
  }
  // First factor at which the tension cut-off or either side of the Coulomb envelope
  // |fs| <= c + fn tan(phi) (residual after failure) is reached along the linear path.
  static double elastic_reach(const Props& p, const State& st, double fn, double fs, double dfn,
                              double dfs) {
    const double tension = st.broken ? 0.0 : p.tension_force;
    const double c = st.broken ? 0.0 : p.cohesion_force;
    const double t = st.broken ? p.tan_phi_res : p.tan_phi;
    double reach = std::numeric_limits<double>::infinity();
    // Each limit as a + s b <= 0: crossed at s = -a / b when b > 0, at once if already past.
    const auto limit = [&](double a, double b) {
      if (b > 0.0)
        reach = std::min(reach, std::max(-a / b, 0.0));
      else if (a > 0.0)
        reach = 0.0;
    };
    limit(-(fn + tension), -dfn);
    if (p.ks > 0.0) {
      limit(fs - c - fn * t, dfs - dfn * t);
      limit(-fs - c - fn * t, -dfs - dfn * t);
    }
    return reach;
  }

  static LawResult evaluate(const ContactKinematics& k, const Props& p, State& st) {
    LawResult r{-p.kn * (k.gap - st.u_dil), 0.0, ContactEvent::none, true};
    if (r.fn < -(st.broken ? 0.0 : p.tension_force)) {
      if (!st.broken) r.event = ContactEvent::tensile_failure;
      st.broken = true;
      r.elastic = false;
      st.fs = 0.0;
      r.fn = 0.0;  // an open joint carries neither tension (residual 0) nor shear
      return r;
    }
    const double fs_trial = st.fs - p.ks * k.du_s;
    double fmax = st.broken ? r.fn * p.tan_phi_res : p.cohesion_force + r.fn * p.tan_phi;
    const double fs_size = std::abs(fs_trial);
    if (fs_size > fmax && fs_size > 0.0) {  // |Fs| > max(Fmax, 0), as two compares: no blend
      r.elastic = false;
      if (!st.broken) {
        r.event = ContactEvent::shear_failure;
        st.broken = true;
        fmax = r.fn * p.tan_phi_res;
      } else {
        r.event = ContactEvent::slip;
      }
      st.fs = std::copysign(std::max(fmax, 0.0), fs_trial);
      if (p.tan_psi > 0.0 && p.ks > 0.0) {
        st.u_dil += std::abs((st.fs - fs_trial) / p.ks) * p.tan_psi;  // opening against Fn
        r.fn = -p.kn * (k.gap - st.u_dil);
      }
    } else {
      st.fs = fs_trial;
    }
    r.fs = st.fs;
    return r;
  }
};

}  // namespace vorodec::laws
