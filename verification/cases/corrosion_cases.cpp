// A11: one stress-corroding contact under a constant stress ratio, stepped by the corrosion
// driver's clock with its forces held, against the quadrature of its time to failure.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "../../src/drivers/corrosion_mode.hpp"
#include "cases.hpp"
#include "vorodec/laws/stress_corrosion.hpp"

namespace vorodec::verification {

namespace {
constexpr double beta = 1e-12;  // m/s (bonded length) or 1/s (strength factor)
constexpr double exponent = 25.8, sigma_t = 10e6, d0 = 1e-3;
const laws::StrengthDegradation degradation{exponent, 0.4, 0.01};
const laws::BondedLength bonded{exponent, 0.0, 0.01};

// Integral of f over [a, b], composite Simpson on n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return sum * h / 3.0;
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

double a11_quadrature(bool bonded_length, double s) {
  if (bonded_length)  // D0 dxi / dt = -beta1 exp(beta2 s / xi), from 1 to xi_f = max(s, xi_a)
    return simpson([&](double xi) { return d0 / (beta * std::exp(exponent * s / xi)); },
                   std::max(s, bonded.xi_a), 1.0, 200000);
  if (s < degradation.m_s) return std::numeric_limits<double>::infinity();
  return simpson([&](double l) { return 1.0 / (beta * std::exp(exponent * s / l)); },
                 std::max(s, degradation.lambda_a), 1.0, 200000);
}

double a11_stepped(bool bonded_length, double s, double n_c, bool frozen) {
  run::CorrosionClock clock(n_c);
  const laws::BondStrength strength{sigma_t, 1e300, 0.0};
  const laws::InitialStrength p0{sigma_t, 1e300, 0.0};
  const laws::ContactStress st{s * sigma_t, 0.0};
  // Per unit of the value: the bonded length as a fraction of D0, or the strength factor.
  const auto rate = [&](double value) {
    if (bonded_length)
      return laws::length_rate(bonded, beta, {-s * sigma_t * d0, 0.0, 0.0, value * d0}, strength) /
             d0;
    return laws::factor_rate(degradation, beta, laws::stress_level(st, p0, value));
  };
  const double floor =
      bonded_length
          ? laws::min_bonded_length(bonded, {-s * sigma_t * d0, 0.0, 0.0, d0}, strength, d0) / d0
          : laws::min_strength_factor(degradation, st, p0);
  double t = 0, value = 1.0;  // xi or lambda
  for (int step = 0; step < 1000000; ++step) {
    const double r = rate(value);
    if (r == 0) return std::numeric_limits<double>::infinity();
    const double dt =
        clock.next(frozen ? laws::time_to(value, floor, r) : laws::held_time(rate, value, floor));
    t += dt;
    value = frozen ? value - r * dt : laws::held_value_after(rate, value, floor, dt);
    if (value <= floor + 1e-12) return t;
    clock.after(false);
  }
  return std::numeric_limits<double>::infinity();
}

CaseResult a11_stress_corrosion(bool bonded_length, double s, double n_c) {
  const auto t0 = std::chrono::steady_clock::now();
  const double ref = a11_quadrature(bonded_length, s),
               got = a11_stepped(bonded_length, s, n_c, false);
  CaseResult c{"A11",
               std::string("one contact under a constant stress ratio ") +
                   (bonded_length ? "(bonded-length reduction, intra-grain)"
                                  : "(strength degradation, grain boundary)") +
                   ": time to failure",
               bonded_length ? "t_f = D0 / beta1 int_{max(s, xi_a)}^1 exp(-beta2 s / xi) dxi"
                             : "t_f = 1 / beta3 int_{max(s, lambda_a)}^1 exp(-beta4 s / lambda) "
                               "dlambda",
               ref,
               got,
               std::isinf(ref) && std::isinf(got) ? 0.0 : std::abs(got - ref) / ref,
               0.01,
               ""};
  c.settings = fmt::format("s = {}, n_c = {}, forces held, time to failure integrated", s, n_c);
  c.seconds = since(t0);
  return c;
}

Ladder a11_frozen_ladder() {
  Ladder l{
      "A11 grain-boundary contact at s = 0.7, the frozen-rate estimate of [Potyondy2007]: time "
      "to failure against n_c",
      "1 / n_c (steps_per_failure 1 ... 256)",
      "time to failure (s)",
      "quadrature t_f = 1 / beta3 int exp(-beta4 s / lambda) dlambda",
      a11_quadrature(false, 0.7),
      {}};
  for (const double n_c : {1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0}) {
    const auto t0 = std::chrono::steady_clock::now();
    const double t = a11_stepped(false, 0.7, n_c, true);
    // The parameter runs the other way (more steps, less error): the ladder takes 1 / n_c.
    l.rungs.push_back(
        {1.0 / n_c, t, std::abs(t - l.reference_value) / l.reference_value, since(t0), n_c == 4.0});
  }
  return l;
}

}  // namespace vorodec::verification
