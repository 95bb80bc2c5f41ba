#pragma once
// Coulomb slip joint with tension cut-off, cohesion, dilation and residual strength
// (docs/theory.md §6.2; UDEC "Coulomb slip with residual strength", 3DEC Mohr-Coulomb joint).
#include <algorithm>
#include <array>
#include <cmath>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/laws/coulomb_strength.hpp"

namespace vorodec::laws {

struct MohrCoulomb {
  static constexpr std::string_view name = "mohr_coulomb";

  struct Params {
    model::Distribution jkn, jks;
    CoulombParams strength;
    model::Distribution dilation;
  };
  // Sampled per contact, already multiplied by the contact length where the law needs forces.
  struct Props {
    double kn, ks;             // N/m
    CoulombStrength strength;  // N (forces: strength x length) and tangents
    double tan_psi;
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
  // A bond with no tension, no cohesion and no friction to lose has nothing to fail: the contact
  // is frictional from the start (no crack event when it first opens or slips; a joint set's
  // clean joints).
  static State initial_state(const Props& p, const NewContact& c) {
    const CoulombStrength& s = p.strength;
    const bool bond =
        c.bonded && (s.tension_force > 0 || s.cohesion_force > 0 || s.tan_phi != s.tan_phi_res);
    return {0.0, c.spring_origin, !bond};
  }
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
    return coulomb_reach(p.strength, st.broken, p.ks > 0.0, fn, fs, dfn, dfs);
  }

  // Stress corrosion degrades the springs and the strength; the spring origin moves so the
  // contact carries fn at its gap (the normal force is in total form).
  static BondView bond(const Props& p, const State& st) {
    return {p.kn,     p.ks, p.strength.tension_force, p.strength.cohesion_force, p.strength.tan_phi,
            st.broken};
  }
  static void set_bond(Props& p, State& st, const BondView& b, double gap, double fn, double fs) {
    p.kn = b.kn;
    p.ks = b.ks;
    p.strength.tension_force = b.tension_force;
    p.strength.cohesion_force = b.cohesion_force;
    st.u_dil = gap + fn / p.kn;
    st.fs = fs;
    st.broken = b.broken;
  }

  // In-situ stress: the contact carries (fn, fs) at its gap, its bond untouched.
  static void preload(const Props& p, State& st, double gap, double fn, double fs) {
    st.u_dil = gap + fn / p.kn;
    st.fs = fs;
  }

  static LawResult evaluate(const ContactKinematics& k, const Props& p, State& st) {
    LawResult r{-p.kn * (k.gap - st.u_dil), 0.0, ContactEvent::none, true};
    if (opens_in_tension(p.strength, st.broken, r)) {
      st.fs = 0.0;  // an open joint carries neither tension (residual 0) nor shear
      return r;
    }
    const double fs_trial = st.fs - p.ks * k.du_s;
    st.fs = cap_shear(p.strength, st.broken, r, fs_trial);
    if (!r.elastic && p.tan_psi > 0.0 && p.ks > 0.0) {
      st.u_dil += std::abs((st.fs - fs_trial) / p.ks) * p.tan_psi;  // opening against Fn
      r.fn = -p.kn * (k.gap - st.u_dil);
    }
    r.fs = st.fs;
    return r;
  }
};

}  // namespace vorodec::laws
