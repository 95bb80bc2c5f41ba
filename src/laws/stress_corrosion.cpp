#include "vorodec/laws/stress_corrosion.hpp"

#include <algorithm>

namespace vorodec::laws {

double min_bonded_length(const BondedLength& law, const BondSection& s, const BondStrength& b,
                         double d0) {
  double d_min = law.xi_a * d0;
  // Tension: the positive root of sigma_s D^2 xi^2 + Fn D xi - bending |M| = 0 ([Liu2020],
  // eq. 18, where bending = 6).
  if (b.tension > 0.0) {
    const double disc = s.fn * s.fn + 4.0 * s.bending * std::abs(s.m) * b.tension;
    d_min = std::max(d_min, (-s.fn + std::sqrt(disc)) / (2.0 * b.tension));
  } else {
    d_min = s.d;  // no tensile strength: nothing left to corrode
  }
  // Shear: |Fs| / (xi D) = c + Fn tan(phi) / (xi D)  ->  xi D = (|Fs| - Fn tan(phi)) / c.
  if (b.cohesion > 0.0) d_min = std::max(d_min, (std::abs(s.fs) - s.fn * b.tan_phi) / b.cohesion);
  return d_min;
}

double stress_level(const ContactStress& s, const InitialStrength& p, double lambda) {
  double m = 0.0;
  if (s.sigma > 0.0)
    m = p.tension > 0.0 ? s.sigma / (lambda * p.tension) : std::numeric_limits<double>::infinity();
  const double tau_s = lambda * p.cohesion - s.sigma * p.tan_phi;  // sigma_n = -sigma
  if (s.tau > 0.0)
    m = std::max(m, tau_s > 0.0 ? s.tau / tau_s : std::numeric_limits<double>::infinity());
  return m;
}

double min_strength_factor(const StrengthDegradation& law, const ContactStress& s,
                           const InitialStrength& p) {
  double lambda = law.lambda_a;
  if (p.tension > 0.0) lambda = std::max(lambda, s.sigma / p.tension);
  if (p.cohesion > 0.0) lambda = std::max(lambda, (s.tau + s.sigma * p.tan_phi) / p.cohesion);
  return lambda;
}

PairSection pair_section(std::span<const PairContact> contacts, double bonded_length) {
  PairSection p;
  double length = 0;
  for (const PairContact& c : contacts) {
    p.section.fn += c.fn;
    p.section.fs += c.fs;
    p.centre += c.length * c.s;
    length += c.length;
  }
  p.centre /= length;
  double reach = 0;
  for (const PairContact& c : contacts) {
    p.section.m += c.fn * (c.s - p.centre);
    p.inertia += c.length * (c.s - p.centre) * (c.s - p.centre);
    reach = std::max(reach, std::abs(c.s - p.centre));
  }
  p.section.d = bonded_length;
  // One point (or points that coincide) carries no moment: the paper's beam stands in.
  if (p.inertia > 0) p.section.bending = reach * length * length / p.inertia;
  return p;
}

std::vector<PairContact> shrink_pair(std::span<const PairContact> contacts, const PairSection& p,
                                     double xi) {
  double length = 0;
  for (const PairContact& c : contacts) length += c.length;
  // fn_i = l_i (a + b (s_i - centre)): sums to a L and to a moment b J.
  const double a = xi * p.section.fn / length;
  const double b = p.inertia > 0 ? xi * xi * xi * p.section.m / p.inertia : 0.0;
  std::vector<PairContact> out(contacts.begin(), contacts.end());
  for (PairContact& c : out) {
    c.fn = c.length * (a + b * (c.s - p.centre));
    c.fs *= xi;
  }
  return out;
}

}  // namespace vorodec::laws
