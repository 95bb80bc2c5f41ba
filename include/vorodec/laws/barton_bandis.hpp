#pragma once
// Rough rock joint (docs/theory.md §6.6): Bandis hyperbolic normal closure, Barton-Choubey peak
// shear strength, post-peak softening by Barton's mobilised JRC and dilation from the mobilised
// roughness [Barton1977, Bandis1983, Barton1982]. A joint carries no tension.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::laws {

struct BartonBandis {
  static constexpr std::string_view name = "barton_bandis";

  struct Params {
    model::Distribution jkn, max_closure, jks, jrc, jcs, residual_friction;
    model::Distribution max_normal_stress;  // constant 0: JCS
  };
  struct Props {
    double kni;     // Pa/m, initial normal stiffness
    double vm;      // m, maximum closure
    double ks;      // Pa/m
    double jrc;     // joint roughness coefficient
    double jcs;     // Pa, joint wall compressive strength
    double phi_r;   // deg, residual (basic) friction angle
    double sn_max;  // Pa, where the hyperbola ends (linear beyond, with its tangent there)
    double length;  // m
  };
  static constexpr std::array<std::string_view, 8> property_names{
      "kni [Pa/m]", "max_closure [m]",   "ks [Pa/m]",   "jrc",
      "jcs [Pa]",   "residual_friction", "sn_max [Pa]", "length [m]"};
  struct State {
    double fs;          // N
    double u_dil;       // m, gap at which the joint closes: NewContact::spring_origin + dilation
    double slide;       // m, shear displacement accumulated (magnitude)
    double slide_peak;  // m, shear displacement when the peak was first reached; 0: not yet
  };

  static Params params_from(const LawParams& p);
  static Props sample(const Params& p, std::uint64_t seed, const NewContact& c);
  static State initial_state(const NewContact& c) { return {0.0, c.spring_origin, 0.0, 0.0}; }

  // Closure (m) at normal stress sn on the hyperbola: sn = kni v / (1 - v / vm).
  static double closure_at(const Props& p, double sn) { return sn * p.vm / (p.kni * p.vm + sn); }
  // Pa/m, the tangent normal stiffness at sn: kni (1 + sn / (kni vm))^2.
  static double tangent_at(const Props& p, double sn) {
    const double r = 1.0 + sn / (p.kni * p.vm);
    return p.kni * r * r;
  }
  // Pa, normal stress at closure v (compression positive; 0 when open).
  static double normal_stress(const Props& p, double v) {
    if (v <= 0.0) return 0.0;
    const double v_max = closure_at(p, p.sn_max);
    if (v < v_max) return p.kni * v / (1.0 - v / p.vm);
    return p.sn_max + tangent_at(p, p.sn_max) * (v - v_max);
  }
  // Closure (m) at normal stress sn, on the hyperbola and on its linear end (normal_stress's
  // inverse).
  static double closure_of(const Props& p, double sn) {
    if (sn <= p.sn_max) return closure_at(p, std::max(sn, 0.0));
    return closure_at(p, p.sn_max) + (sn - p.sn_max) / tangent_at(p, p.sn_max);
  }
  // In-situ stress: the joint closed to carry fn at its gap, and the shear force fs.
  static void preload(const Props& p, State& st, double gap, double fn, double fs) {
    st.u_dil = gap + closure_of(p, fn / p.length);
    st.fs = fs;
  }
  static double max_stiffness(const Props& p) {
    return std::max(tangent_at(p, p.sn_max), p.ks) * p.length;
  }
  // J per m: the hyperbola's area kni vm^2 (u - 1 - ln u), u = 1 - v / vm, and the linear part.
  static double strain_energy(const Props& p, double fn, double fs) {
    const double sn = std::max(fn / p.length, 0.0), s1 = std::min(sn, p.sn_max);
    const double u = p.kni * p.vm / (p.kni * p.vm + s1);
    double e = p.kni * p.vm * p.vm * (u - 1.0 - std::log(u));
    if (sn > p.sn_max) e += (sn * sn - p.sn_max * p.sn_max) / (2.0 * tangent_at(p, p.sn_max));
    return p.length * e + (p.ks > 0.0 ? 0.5 * fs * fs / (p.ks * p.length) : 0.0);
  }

  // JRC_mob / JRC after the peak, against slide / slide_peak [Barton1982, Table 1], linear in
  // log10 of the ratio between the table's points.
  static double mobilised(double ratio) {
    static constexpr std::array<double, 5> at{1, 2, 4, 10, 100};
    static constexpr std::array<double, 5> share{1.0, 0.85, 0.70, 0.50, 0.0};
    if (ratio <= 1.0) return 1.0;
    for (std::size_t i = 1; i < at.size(); ++i)
      if (ratio < at[i])
        return share[i - 1] + (share[i] - share[i - 1]) * std::log10(ratio / at[i - 1]) /
                                  std::log10(at[i] / at[i - 1]);
    return 0.0;
  }
  // The roughness term JRC log10(JCS / sn) in degrees, never negative.
  static double roughness(const Props& p, double jrc, double sn) {
    return std::max(jrc * std::log10(p.jcs / sn), 0.0);
  }
  // Peak (or mobilised) friction angle in degrees, at most 70 deg [Barton1977].
  static double friction_angle(const Props& p, double jrc, double sn) {
    return std::min(roughness(p, jrc, sn) + p.phi_r, 70.0);
  }
  static double tan_deg(double deg) { return std::tan(deg * std::numbers::pi / 180.0); }

  static LawResult evaluate(const ContactKinematics& k, const Props& p, State& st) {
    st.slide += std::abs(k.du_s);
    const double sn = normal_stress(p, st.u_dil - k.gap);
    LawResult r{sn * p.length, 0.0, ContactEvent::none, true};
    if (sn <= 0.0) {  // open: no tension, no shear
      st.fs = 0.0;
      return r;
    }
    const double jrc = st.slide_peak > 0.0 ? p.jrc * mobilised(st.slide / st.slide_peak) : p.jrc;
    const double fmax = r.fn * tan_deg(friction_angle(p, jrc, sn));
    const double ks = p.ks * p.length;
    const double fs_trial = st.fs - ks * k.du_s;
    if (std::abs(fs_trial) <= fmax) {
      st.fs = r.fs = fs_trial;
      return r;
    }
    r.elastic = false;
    r.event = ContactEvent::slip;
    if (st.slide_peak == 0.0) st.slide_peak = std::max(st.slide, 1e-300);
    st.fs = r.fs = std::copysign(fmax, fs_trial);
    // Dilation at half the mobilised roughness: the joint opens against the normal force.
    const double plastic = (std::abs(fs_trial) - fmax) / ks;
    st.u_dil += plastic * tan_deg(0.5 * roughness(p, jrc, sn));
    r.fn = normal_stress(p, st.u_dil - k.gap) * p.length;
    return r;
  }
};

}  // namespace vorodec::laws
