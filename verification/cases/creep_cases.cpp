// A10: one Burger's contact under a constant force against the analytic creep curve
// u(t) = F/Km + F t/Cm + F/Kk (1 - exp(-Kk t/Ck)) (docs/theory.md §13.2), normal and shear.
#include <chrono>
#include <cmath>

#include "cases.hpp"
#include "vorodec/laws/burgers.hpp"

namespace vorodec::verification {

namespace {

using laws::Burgers;

constexpr double L = 1e-3;          // m, contact length
constexpr double F = 1e4;           // N, the held force
constexpr double tau_k = 1e4;       // s, Kelvin retardation time Ck/Kk
constexpr double t_end = 5e4;       // s, five retardation times: primary creep has run its course
constexpr double default_dt = 1e2;  // s, tau_k / 100

Burgers::Props contact() {
  // Per unit length, sandstone-like: Kmn 2e13 Pa/m, Cmn 2e18 Pa s/m (Cm/Km = 1e5 s), Kkn 5e13
  // Pa/m, Ckn 5e17 Pa s/m; shear the same ([Guo2020] sets the ratios to 1).
  const laws::BurgersChain e{2e13 * L, 2e18 * L, 5e13 * L, 5e17 * L};
  return {e, e, {1e300, 1e300, 0.6, 0.6}, 1.0};
}

double exact(const Burgers::Props& p, double t) {
  const laws::BurgersChain& e = p.normal;
  return F / e.km + F * t / e.cm + F / e.kk * (1.0 - std::exp(-e.kk * t / e.ck));
}

struct CreepRun {
  double u = 0;      // m, displacement at t_end
  double worst = 0;  // largest relative error over the steps
};

// Holds the force at F: each step takes the displacement increment that makes the new force F.
// The force is affine in the increment, so two trial evaluations on copies of the state give it
// exactly. consistent: start from f = F, u = F/Km (the instantaneous response); otherwise from
// rest, with the force stepped up to F in the first step.
CreepRun hold_force(bool shear, bool consistent, double dt) {
  const Burgers::Props p = contact();
  Burgers::State st{0, 0, 0, 0, 0, 0, false};
  double u = 0;
  if (consistent) {
    u = F / p.normal.km;
    (shear ? st.fs : st.fn) = F;
  }
  // The step's kinematics for a displacement increment du: the normal one through the gap
  // (opening positive, so gap = -u), the shear one as an increment (force = -ks du_s).
  const auto kinematics = [&](double du) -> laws::ContactKinematics {
    return shear ? laws::ContactKinematics{0.0, 0.0, -du, L, dt}
                 : laws::ContactKinematics{-(u + du), -du, 0.0, L, dt};
  };
  const auto force = [&](Burgers::State s, double du) {
    double w = 0;
    const auto r = Burgers::evaluate(kinematics(du), p, s, w);
    return shear ? r.fs : r.fn;
  };
  CreepRun run;
  const long steps = std::lround(t_end / dt);
  for (long n = 1; n <= steps; ++n) {
    const double f0 = force(st, 0.0), f1 = force(st, 1e-6);
    const double du = (F - f0) * 1e-6 / (f1 - f0);
    double w = 0;
    Burgers::evaluate(kinematics(du), p, st, w);
    u += du;
    const double ref = exact(p, double(n) * dt);
    run.worst = std::max(run.worst, std::abs(u - ref) / ref);
  }
  run.u = u;
  return run;
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

CaseResult a10_burgers_creep(bool shear) {
  const auto t0 = std::chrono::steady_clock::now();
  const CreepRun r = hold_force(shear, true, default_dt);
  CaseResult c{"A10",
               std::string("Burger's contact under a constant force, ") +
                   (shear ? "shear" : "normal") + ": worst error over 5 retardation times",
               "u(t) = F/Km + F t/Cm + F/Kk (1 - exp(-Kk t/Ck))",
               exact(contact(), t_end),
               r.u,
               r.worst,
               1e-3,
               "dt = Ck/Kk / 100, consistent start f = F, u = F/Km"};
  c.seconds = since(t0);
  return c;
}

std::vector<Ladder> a10_ladders() {
  std::vector<Ladder> out;
  for (const bool consistent : {true, false}) {
    Ladder l{std::string("A10 Burger's contact creep, normal, ") +
                 (consistent ? "consistent start" : "force stepped up from zero") +
                 ": displacement at 5 Ck/Kk against time step",
             "time step (s), Ck/Kk / 10 ... / 640",
             "u(5 Ck/Kk) (m)",
             "exact u = F/Km + F t/Cm + F/Kk (1 - exp(-Kk t/Ck))",
             exact(contact(), t_end),
             {}};
    for (const double dt : {1e3, 5e2, 2.5e2, 1.25e2, 62.5, 31.25, 15.625}) {
      const auto t0 = std::chrono::steady_clock::now();
      const CreepRun r = hold_force(false, consistent, dt);
      l.rungs.push_back({dt, r.u, std::abs(r.u - l.reference_value) / l.reference_value, since(t0),
                         dt == 1.25e2});
    }
    out.push_back(l);
  }
  return out;
}

}  // namespace vorodec::verification
