#pragma once
// The two stress-corrosion degradation layers (docs/theory.md §14; [Potyondy2007]'s PSC,
// [Liu2020]'s GSC). Each sits on a bonded Mohr-Coulomb contact and changes only what the strength
// layer (coulomb_strength.hpp) reads: a layer gives the contact's corrosion rate, how far it can
// degrade before one of its break conditions is met (forces held), and the degraded section.
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace vorodec::laws {

// beta1(rs) = (beta_up - beta_low) / (1 + exp(k_v (rs - r_mid))) + beta_low ([Liu2020], eq. 6):
// the rate constant of a corrosion stage at driving-stress ratio rs; k_v < 0 makes it rise with rs.
struct DrivingRate {
  double beta_up, beta_low, r_mid, k_v;
  double at(double rs) const {
    return (beta_up - beta_low) / (1.0 + std::exp(k_v * (rs - r_mid))) + beta_low;
  }
};

// --- Inside grains: bonded-length reduction (PSC) ---
// A bonded section of unit thickness: A = D, I = k_I D^3 and R = k_R D, so that shrinking D to
// xi D scales A by xi and I by xi^3 as the paper's 2D beam (k_I = 1/12, k_R = 1/2). `bending` is
// R D^2 / I = k_R / k_I: 6 for the paper's beam; pair_section gives a joint's own.
struct BondSection {
  double fn;  // N, normal force, compression positive
  double fs;  // N, shear force
  double m;   // N m, moment about the section's centre
  double d;   // m, bonded length
  double bending = 6.0;
};
// The bond's strengths (stresses) and its friction; the shear strength is c + sigma_n tan(phi),
// sigma_n = Fn / A (compression positive), as the Coulomb layer has it.
struct BondStrength {
  double tension, cohesion, tan_phi;  // Pa, Pa, -
};
struct BondedLength {
  double beta2;              // -, stress exponent
  double activation_stress;  // Pa, sigma_a: no corrosion below it
  double xi_a;               // -, the bond breaks when D < xi_a D0
};

// Pa, the largest tensile stress of the section, -Fn / A + |M| R / I (tension positive).
inline double bond_tension(const BondSection& s) {
  return -s.fn / s.d + s.bending * std::abs(s.m) / (s.d * s.d);
}
// Pa, the shear stress |Fs| / A.
inline double bond_shear(const BondSection& s) {
  return std::abs(s.fs) / s.d;
}
// The section fails: tension or shear strength reached.
inline bool bond_fails(const BondSection& s, const BondStrength& b) {
  return bond_tension(s) >= b.tension || bond_shear(s) >= b.cohesion + s.fn / s.d * b.tan_phi;
}
// m/s, zeta = beta1 exp(beta2 sigma / sigma_s) for sigma_a <= sigma < sigma_s, else 0.
inline double length_rate(const BondedLength& law, double beta1, const BondSection& s,
                          const BondStrength& b) {
  const double sigma = bond_tension(s);
  if (sigma < law.activation_stress || sigma >= b.tension) return 0.0;
  return beta1 * std::exp(law.beta2 * sigma / b.tension);
}
// m, D_min: the largest bonded length at which the section, its forces held, breaks in tension
// (sigma_s D^2 xi^2 + Fn D xi - bending |M| = 0), in shear (|Fs| = xi D c + Fn tan(phi)), or by
// D < xi_a D0.
double min_bonded_length(const BondedLength& law, const BondSection& s, const BondStrength& b,
                         double d0);

// vorodec's mapping of a sub-block joint onto the beam section. The joint is its bonded point
// contacts (one at each end). D is the bonded length, at first the joint's length D0 (the sum of
// the contacts' lengths), and A = D. Fn and Fs are the contacts' sums, M their normal forces'
// moment about the length-weighted centre of their points. I and R are the pair's own at D0: I0 =
// J = sum l_i (s_i - centre)^2 (about D0^3 / 4, where a continuous beam has D0^3 / 12) and R0 the
// farthest point's distance, so bending = R0 D0^2 / J (about 2, not 6): at D0 the section's stress
// is the larger of its contacts' stresses, and the corrosion stage's break check agrees with the
// contacts' own tension cut-off. Shrinking D to xi D (I to xi^3 I, R to xi R) at unchanged
// displacements gives F' = xi F, M' = xi^3 M (shrink_pair); the contacts' springs and strengths
// scale by xi. The points do not move: between corrosion steps the pair turns on xi jkn J, where
// the shrunk beam would have xi^3 jkn J; each step restores the beam's forces.
struct PairSection {
  BondSection section{0, 0, 0, 0};
  double centre = 0;   // m, along the joint
  double inertia = 0;  // m^3, sum of l_i (s_i - centre)^2: the pair's second moment of length
};
struct PairContact {
  double fn, fs, s, length;  // N, N, m along the joint, m
};
PairSection pair_section(std::span<const PairContact> contacts, double bonded_length);
// Forces of the pair after the section shrinks from D to D' = xi D at unchanged displacements:
// F' = xi F and M' = xi^3 M (the 2D beam), spread over the contacts linearly along the joint.
std::vector<PairContact> shrink_pair(std::span<const PairContact> contacts, const PairSection& p,
                                     double xi);

// --- On grain boundaries: strength degradation (GSC) ---
// The tensile strength and cohesion of the contact are lambda x their initial values; lambda falls
// at beta3 exp(beta4 m) for m_s <= m < 1, m = max(sigma / sigma_t, |tau| / tau_s),
// tau_s = lambda c0 + sigma_n tan(phi).
struct StrengthDegradation {
  double beta4;     // -, stress-level exponent
  double m_s;       // -, activation stress level
  double lambda_a;  // -, lower bound of lambda
};
// A grain-boundary contact's stresses on its length (Pa): tension positive, |shear|.
struct ContactStress {
  double sigma, tau;
};
struct InitialStrength {
  double tension, cohesion, tan_phi;  // Pa, Pa, -
};
// -, m at degradation factor lambda (infinity where the shear strength is gone).
double stress_level(const ContactStress& s, const InitialStrength& p, double lambda);
// 1/s, -d lambda / dt.
inline double factor_rate(const StrengthDegradation& law, double beta3, double m) {
  return m >= law.m_s && m < 1.0 ? beta3 * std::exp(law.beta4 * m) : 0.0;
}
// -, lambda_min: the largest factor at which the contact, its stresses held, breaks in tension
// (sigma = lambda sigma_t0) or shear (|tau| = lambda c0 + sigma_n tan(phi)), or lambda_a.
double min_strength_factor(const StrengthDegradation& law, const ContactStress& s,
                           const InitialStrength& p);

// --- Integrating a layer with its forces held ---
// s, time to reach `floor` from `value` at a constant `rate` (per s); infinity at
// rate 0 ([Potyondy2007]'s estimate: the rate frozen where it is).
inline double time_to(double value, double floor, double rate) {
  if (rate <= 0.0) return std::numeric_limits<double>::infinity();
  return std::max(value - floor, 0.0) / rate;
}

// A degrading value v (a bonded length or a strength factor) falling at rate(v) > 0 per s, its
// forces held, from `from` down to `floor`: the exact time, int_floor^from dv / rate(v), on
// `panels` panels of 5-point Gauss-Legendre (rate(v) is exponential in the stress, which grows
// as v falls: a panel spans a small change of its exponent).
inline constexpr int held_panels = 32;
namespace detail {
// int_a^b dv / rate(v), one 5-point Gauss-Legendre panel.
template <class Rate>
double gauss_panel(const Rate& rate, double a, double b) {
  static constexpr double x[] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                 0.9061798459386640};
  static constexpr double w[] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                 0.2369268850561891, 0.2369268850561891};
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double t = 0.0;
  for (int k = 0; k < 5; ++k) t += w[k] / rate(mid + half * x[k]);
  return half * t;
}
}  // namespace detail

template <class Rate>
double held_time(const Rate& rate, double from, double to) {
  if (!(from > to)) return 0.0;
  const double h = (from - to) / held_panels;
  double t = 0.0;
  for (int p = 0; p < held_panels; ++p)
    t += detail::gauss_panel(rate, to + p * h, to + (p + 1) * h);
  return t;
}
// Whether held_time(rate, from, to) exceeds `limit` (s), from as few panels as that takes: the
// panels from the top down (the slowest rates, the largest part of the integral), until their
// partial sum passes the limit by more than the rounding of held_time's own sum (a relative
// 1e-9). False when the whole integral does not pass it that clearly. A corrosion step skips the
// integral of every item this shows slower than the fastest so far (CorrosionControl).
template <class Rate>
bool held_time_exceeds(const Rate& rate, double from, double to, double limit) {
  if (!(from > to)) return 0.0 > limit;
  const double h = (from - to) / held_panels;
  double t = 0.0;
  for (int p = held_panels - 1; p >= 0; --p) {
    t += detail::gauss_panel(rate, to + p * h, to + (p + 1) * h);
    if (t * (1 - 1e-9) > limit) return true;
  }
  return false;
}
// Where the value is after dt (s) from `from` on the same panels (at least `floor`): the panel the
// time runs out in, then bisection inside it to a 1e-12 part of the span (or
// the last bit).
template <class Rate>
double held_value_after(const Rate& rate, double from, double floor, double dt) {
  if (!(from > floor)) return floor;
  const double h = (from - floor) / held_panels;
  double left = dt;
  for (int p = held_panels - 1; p >= 0; --p) {  // from the top down
    const double a = floor + p * h, b = a + h, t = detail::gauss_panel(rate, a, b);
    if (t < left) {
      left -= t;
      continue;
    }
    double lo = a, hi = b;  // time from b down to lo >= left >= time down to hi
    for (int i = 0; i < 60 && hi - lo > 1e-12 * (from - floor); ++i) {  // 60: past any ulp
      const double mid = 0.5 * (lo + hi);
      (detail::gauss_panel(rate, mid, b) > left ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
  return floor;
}

}  // namespace vorodec::laws
