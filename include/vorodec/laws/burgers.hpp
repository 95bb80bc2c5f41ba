#pragma once
// Burger's contact (docs/theory.md §13; PFC's Burger's model, [Guo2020]): in the normal and in the
// shear direction a Kelvin element (Kk, Ck in parallel) in series with a Maxwell element (Km, Cm
// in series), integrated by the trapezoidal rule, with the Mohr-Coulomb strength layer on the
// same contact: tension cut-off, cohesion and the friction slider.
#include <algorithm>
#include <array>
#include <cmath>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/laws/coulomb_strength.hpp"

namespace vorodec::laws {

// One direction's Kelvin + Maxwell chain: force f and Kelvin displacement uk carried between
// steps; the Maxwell dashpot's displacement is implied (normal: kept, for the total form).
struct BurgersChain {
  double km, cm, kk, ck;  // N/m and N s/m (per contact: per unit length x length)
};

// Step coefficients of docs/theory.md §13.2 for one direction and time step: with
// A = 1 + Kk dt / (2 Ck), B = 1 - Kk dt / (2 Ck), the force line
// f1 = (du + (1 - B/A) uk - D f0) / C and the Kelvin line uk1 = (B uk + dt / (2 Ck) (f0 + f1)) / A.
struct BurgersStep {
  double b_over_a, half_dt_ck_a, half_dt_cm, c, d;
  BurgersStep(const BurgersChain& e, double dt)
      : b_over_a((1.0 - e.kk * dt / (2.0 * e.ck)) / (1.0 + e.kk * dt / (2.0 * e.ck))),
        half_dt_ck_a(dt / (2.0 * e.ck * (1.0 + e.kk * dt / (2.0 * e.ck)))),
        half_dt_cm(dt / (2.0 * e.cm)),
        c(half_dt_ck_a + 1.0 / e.km + half_dt_cm),
        d(half_dt_ck_a - 1.0 / e.km + half_dt_cm) {}
  double kelvin(double uk, double f0, double f1) const {
    return b_over_a * uk + half_dt_ck_a * (f0 + f1);
  }
};

struct Burgers {
  static constexpr std::string_view name = "burgers";
  // evaluate reports the dashpots' dissipation of the step (LawGroupOf adds it to its own term).
  static constexpr bool viscous = true;

  struct Params {
    model::Distribution kmn, cmn, kkn, ckn, kms, cms, kks, cks;
    CoulombParams strength;
    bool carry_tension;
  };
  struct Props {
    BurgersChain normal, shear;
    CoulombStrength strength;
    double carries_tension;  // 1: no tension cut-off (PFC's mode 0); 0: the strength layer's
  };
  static constexpr std::array<std::string_view, 13> property_names{
      "kmn [N/m]",   "cmn [N s/m]", "kkn [N/m]",      "ckn [N s/m]",       "kms [N/m]",
      "cms [N s/m]", "kks [N/m]",   "cks [N s/m]",    "tension_force [N]", "cohesion_force [N]",
      "tan_phi",     "tan_phi_res", "carries_tension"};
  struct State {
    double fn, ukn, umn;  // N, m, m: normal force, Kelvin and Maxwell-dashpot displacements
    double origin;        // m, gap at which the contact was unloaded when it appeared
    double fs, uks;       // N, m: shear force and Kelvin displacement
    bool broken;          // bond lost (or never had one): residual friction, no tension
  };

  static Params params_from(const LawParams& p);
  static Props sample(const Params& p, std::uint64_t seed, const NewContact& c);
  // A contact with neither tension nor cohesion has no bond to lose: frictional from the start
  // (no crack event when it first opens or slips).
  static State initial_state(const Props& p, const NewContact& c) {
    const bool bond = c.bonded && (p.strength.tension_force > 0 || p.strength.cohesion_force > 0);
    return {0.0, 0.0, 0.0, c.spring_origin, 0.0, 0.0, !bond};
  }
  static double max_stiffness(const Props& p) { return std::max(p.normal.km, p.shear.km); }
  // s, the shortest relaxation time of the contact's elements (creep time step).
  static double relaxation_time(const Props& p) {
    return std::min({p.normal.ck / p.normal.kk, p.normal.cm / p.normal.km, p.shear.ck / p.shear.kk,
                     p.shear.cm / p.shear.km});
  }
  // J per m: the Maxwell springs (from the forces) and the Kelvin springs (from the state).
  static double strain_energy(const Props& p, const State& st, double fn, double fs) {
    return 0.5 * (fn * fn / p.normal.km + p.normal.kk * st.ukn * st.ukn + fs * fs / p.shear.km +
                  p.shear.kk * st.uks * st.uks);
  }

  static LawResult evaluate(const ContactKinematics& k, const Props& p, State& st,
                            double& viscous) {
    const BurgersStep n(p.normal, k.dt), s(p.shear, k.dt);
    // Normal in total form from the gap (compression positive), so an open contact closes
    // again where its Maxwell spring is unloaded: u = uk + f/Km + umn.
    const double u = st.origin - k.gap;
    LawResult r{(u - st.umn - n.b_over_a * st.ukn - (n.half_dt_ck_a + n.half_dt_cm) * st.fn) / n.c,
                0.0, ContactEvent::none, false};
    double fs1 = 0.0;
    if (p.carries_tension != 0.0 || !opens_in_tension(p.strength, st.broken, r)) {
      // Shear incrementally (the force line), like the Mohr-Coulomb joint's shear spring.
      const double fs_trial = (-k.du_s + (1.0 - s.b_over_a) * st.uks - s.d * st.fs) / s.c;
      fs1 = cap_shear(p.strength, st.broken, r, fs_trial);
      r.elastic = false;  // the dashpots dissipate in every step
    }
    viscous = dissipate(p.normal, n, st.fn, r.fn, st.ukn, k.dt) +
              dissipate(p.shear, s, st.fs, fs1, st.uks, k.dt);
    st.umn += n.half_dt_cm * (st.fn + r.fn);
    st.fn = r.fn;
    st.fs = r.fs = fs1;
    return r;
  }

 private:
  // Advances the Kelvin displacement uk over the step from f0 to f1 and returns the dashpots'
  // work (trapezoidal, so the energy balance closes exactly): Maxwell dt/(4 Cm) (f0 + f1)^2,
  // Kelvin Ck (duk)^2 / dt.
  static double dissipate(const BurgersChain& e, const BurgersStep& st, double f0, double f1,
                          double& uk, double dt) {
    const double uk1 = st.kelvin(uk, f0, f1), duk = uk1 - uk;
    uk = uk1;
    return st.half_dt_cm * 0.5 * (f0 + f1) * (f0 + f1) + e.ck * duk * duk / dt;
  }
};

}  // namespace vorodec::laws
