#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include "cases.hpp"
#include "scenes.hpp"
#include "vorodec/geometry/tessellation.hpp"
#include "vorodec/laws/mohr_coulomb.hpp"
#include "vorodec/model/polygon.hpp"
#include "vorodec/model/weibull.hpp"

namespace vorodec::verification {

using model::Group;

namespace {

constexpr double rho = 2600, a = 0.01;  // kg/m^3, block size m

double rel(double measured, double expected) {
  return std::abs(measured - expected) / std::abs(expected);
}

double tand(double deg) {
  return std::tan(deg * std::numbers::pi / 180.0);
}

}  // namespace

CaseResult a1_mass_properties() {
  return timed({"A1", "polygon area and polar inertia, 200 random regular polygons",
                "exact: A = n r^2 sin(2pi/n)/2, J = A r^2 (2 + cos(2pi/n))/6", 0, 0, 0, 1e-12,
                "relative to vertex 0"},
               [](CaseResult& r) {
                 std::mt19937_64 rng(5);
                 std::uniform_real_distribution<double> u(0.0, 1.0);
                 double worst = 0;
                 for (int trial = 0; trial < 200; ++trial) {
                   const int n = 3 + static_cast<int>(u(rng) * 10);
                   const double rad = 1e-3 * (0.5 + u(rng)), phase = u(rng) * 6.28;
                   const model::Point c{u(rng) * 0.1, u(rng) * 0.1};
                   std::vector<model::Point> p;
                   for (int i = 0; i < n; ++i) {
                     const double t = phase + 2 * std::numbers::pi * i / n;
                     p.push_back({c.x + rad * std::cos(t), c.y + rad * std::sin(t)});
                   }
                   const auto m = model::mass_properties(p);
                   const double t = 2 * std::numbers::pi / n;
                   const double area = 0.5 * n * rad * rad * std::sin(t);
                   worst =
                       std::max({worst, rel(m.area, area),
                                 rel(m.polar_moment, area * rad * rad * (2 + std::cos(t)) / 6)});
                 }
                 r.error = r.measured = worst;
               });
}

CaseResult a2_tessellation_area() {
  return timed(
      {"A2", "sum of block areas = outline area (1302 blocks, 2 Lloyd, collapse 0.25 mm)",
       "exact outline area 5000 mm^2; same seed -> identical blocks", 5e-3, 0, 0, 1e-9, "seed 42"},
      [](CaseResult& r) {
        geometry::TessellationSettings s;
        s.outline = {geometry::OutlineKind::rectangle, 0.05, 0.1, 0, 0};
        s.block_count = 1302;
        s.seed = 42;
        s.lloyd_iterations = 2;
        s.min_edge_length = 2.5e-4;
        const auto t = geometry::tessellate(s);
        double area = 0;
        std::vector<model::Point> p;
        for (const auto& b : t.blocks) {
          p.clear();
          for (auto v : b) p.push_back(t.vertices[v]);
          area += model::mass_properties(p).area;
        }
        r.measured = area;
        r.error = rel(area, r.expected);
        const auto again = geometry::tessellate(s);
        const bool same = again.blocks == t.blocks &&
                          std::equal(t.vertices.begin(), t.vertices.end(), again.vertices.begin(),
                                     [](auto x, auto y) { return x.x == y.x && x.y == y.y; });
        if (!same) r.error = 1.0;  // reproducibility is part of the case
      });
}

namespace {
// Two bonded squares side by side, pushed apart, undamped (A3).
struct PairRun {
  double period_measured, period_expected, energy_drift, dt;
};

PairRun bonded_pair(double safety) {
  model::Model m;
  m.rounding_length = 0.01 * a;
  model::add_block(m, square(0, 0, a), rho, Group::specimen);
  model::add_block(m, square(a, 0, a), rho, Group::specimen);
  solver::SolverSettings s;
  s.local_damping = 0.0;
  s.safety_factor = safety;
  const double jkn = 1e10;
  auto solver = make_solver(m, "linear_elastic", params({{"jkn", jkn}, {"jks", jkn}}), s);
  const double period = 2 * std::numbers::pi * std::sqrt(rho * a * a / 2 / (jkn * a));
  m.blocks.vx[0] = 0.01;
  m.blocks.vx[1] = -0.01;
  const double sep0 = m.blocks.x[1] - m.blocks.x[0];
  std::vector<double> crossings;
  double prev = 0, e0 = 0, drift = 0;
  auto& bl = m.blocks;
  while (solver->time() < 100.5 * period) {
    const std::vector<double> vx = bl.vx, vy = bl.vy, om = bl.omega;
    solver->step();
    const double u = (bl.x[1] - bl.x[0]) - sep0;
    if (prev < 0 && u >= 0) crossings.push_back(solver->time() - solver->dt() * u / (u - prev));
    prev = u;
    // The leapfrog's conserved energy: the kinetic energy time-centred as 1/2 m v(n-1/2).v(n+1/2)
    // (the plain sum oscillates within a period by the half-step offset).
    double e = solver->contact_strain_energy();
    for (std::size_t b = 0; b < bl.size(); ++b)
      e += 0.5 * (bl.mass[b] * (vx[b] * bl.vx[b] + vy[b] * bl.vy[b]) +
                  bl.inertia[b] * om[b] * bl.omega[b]);
    if (e0 == 0) e0 = e;
    drift = std::max(drift, std::abs(e / e0 - 1.0));
  }
  const double measured = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  return {measured, period, drift, solver->dt()};
}
}  // namespace

CaseResult a3_bonded_pair_period() {
  return timed({"A3", "bonded pair, free normal oscillation: period",
                "T = 2 pi sqrt(m_eff / (jkn L)), m_eff = m/2", 0, 0, 0, 5e-3,
                "safety factor 0.1, no damping"},
               [](CaseResult& r) {
                 const PairRun p = bonded_pair(0.1);
                 r.expected = p.period_expected;
                 r.measured = p.period_measured;
                 r.error = rel(r.measured, r.expected);
               });
}

CaseResult a3_bonded_pair_energy_drift() {
  return timed({"A3", "bonded pair: energy drift over 100 periods",
                "kinetic (time-centred) + strain energy constant: max deviation", 0, 0, 0, 1e-4,
                "safety factor 0.1, no damping"},
               [](CaseResult& r) { r.error = r.measured = bonded_pair(0.1).energy_drift; });
}

CaseResult a4_incline(double angle_deg) {
  const double phi = 30.0, g = 9.81, theta = angle_deg * std::numbers::pi / 180;
  const double expected = g * (std::sin(theta) - std::cos(theta) * tand(phi));
  CaseResult r{"A4",
               "block on a " + std::to_string(int(angle_deg)) + " deg incline, friction 30 deg",
               expected > 0 ? "a = g (sin theta - cos theta tan phi)" : "sticks: theta < phi",
               std::max(expected, 0.0),
               0,
               0,
               expected > 0 ? 0.01 : 1e-6,
               expected > 0 ? "undamped, safety factor 0.2" : "damping 0.8 (judged at rest)"};
  return timed(r, [&](CaseResult& c) {
    model::Model m;
    m.rounding_length = 0.01 * a;
    model::add_block(m, square(0, a, a), rho, Group::specimen);
    model::add_block(m, std::vector<model::Point>{{-1, 0}, {1, 0}, {1, a}, {-1, a}}, rho,
                     Group::bottom_platen);
    solver::SolverSettings s;
    s.local_damping = expected > 0 ? 0.0 : 0.8;
    s.safety_factor = 0.2;
    s.gravity = {g * std::sin(theta), -g * std::cos(theta)};
    auto solver = make_solver(m, "mohr_coulomb",
                              params({{"jkn", 1e11},
                                      {"jks", 1e11},
                                      {"friction", phi},
                                      {"tension", 0},
                                      {"cohesion", 0},
                                      {"dilation", 0},
                                      {"residual_friction", phi}}),
                              s);
    // Start at the static overlap under the normal weight: a block dropped onto the platen from
    // touching would bounce (no damping) and lose its shear force at every lift-off.
    double kn = 0.0;
    for (std::size_t i = 0; i < m.contacts.size(); ++i) kn += solver->laws()[0]->properties(i)[0];
    m.blocks.y[0] -= m.blocks.gravity_mass[0] * g * std::cos(theta) / kn;
    while (solver->time() < 0.02) solver->step();
    const double t1 = solver->time(), v1 = m.blocks.vx[0];
    while (solver->time() < 0.12) solver->step();
    if (expected > 0) {
      c.measured = (m.blocks.vx[0] - v1) / (solver->time() - t1);
      c.error = rel(c.measured, expected);
    } else {
      c.error = c.measured = std::abs(m.blocks.x[0] - 0.5 * a);  // m moved: elastic creep only
    }
  });
}

namespace {
constexpr double L = 1e-3, sn = 10e6;
laws::MohrCoulomb::Props marble_joint(double dilation_deg) {
  return {1e13 * L, 4e12 * L, 14e6 * L, 24e6 * L, tand(25.5), tand(20.0), tand(dilation_deg)};
}
// Direct shear under constant normal stress sn: peak and last shear force.
std::pair<double, double> direct_shear() {
  const auto p = marble_joint(0.0);
  laws::MohrCoulomb::State st{0.0, 0.0, false};
  double peak = 0, last = 0;
  for (int i = 0; i < 4000; ++i) {
    const auto r = laws::MohrCoulomb::evaluate({-sn * L / p.kn, 0.0, -1e-8, L, 1e-7}, p, st);
    peak = std::max(peak, std::abs(r.fs));
    last = std::abs(r.fs);
  }
  return {peak, last};
}
}  // namespace

CaseResult a5_direct_shear_peak() {
  return timed({"A5", "direct shear of a bonded joint, sn = 10 MPa: peak", "tau = c + sn tan(phi)",
                (24e6 + sn * tand(25.5)) * L, 0, 0, 0.01, "shear increments 1e-8 m"},
               [](CaseResult& r) {
                 r.measured = direct_shear().first;
                 r.error = rel(r.measured, r.expected);
               });
}

CaseResult a5_direct_shear_residual() {
  return timed({"A5", "direct shear: residual", "tau_r = sn tan(phi_r)", sn * tand(20.0) * L, 0, 0,
                0.01, "shear increments 1e-8 m"},
               [](CaseResult& r) {
                 r.measured = direct_shear().second;
                 r.error = rel(r.measured, r.expected);
               });
}

CaseResult a5_dilation() {
  return timed({"A5", "dilation under constant normal stress (psi = 18 deg)",
                "normal opening / slip = tan(psi)", tand(18.0), 0, 0, 0.01, "normal-stress servo"},
               [](CaseResult& r) {
                 const auto p = marble_joint(18.0);
                 laws::MohrCoulomb::State st{0.0, 0.0, true};
                 double gap = -5e6 * L / p.kn, slip = 0;
                 const double gap0 = gap;
                 for (int i = 0; i < 2000; ++i) {
                   const double fs_before = st.fs;
                   const auto res = laws::MohrCoulomb::evaluate({gap, 0.0, -1e-7, L, 1e-7}, p, st);
                   if (res.event == laws::ContactEvent::slip)
                     slip += 1e-7 - (st.fs - fs_before) / p.ks;
                   gap = st.u_dil - 5e6 * L / p.kn;
                 }
                 r.measured = (gap - gap0) / slip;
                 r.error = rel(r.measured, r.expected);
               });
}

CaseResult a6_direct_tension() {
  return timed(
      {"A6", "direct tension of a bonded joint", "breaks at T L", 14e6 * L, 0, 0, 0.01,
       "normal increments 1e-10 m"},
      [](CaseResult& r) {
        const auto p = marble_joint(0.0);
        laws::MohrCoulomb::State st{0.0, 0.0, false};
        for (int i = 1; i < 1000000 && !st.broken; ++i) {
          const auto res = laws::MohrCoulomb::evaluate({i * 1e-10, 1e-10, 0.0, L, 1e-7}, p, st);
          if (!st.broken) r.measured = std::max(r.measured, -res.fn);
        }
        r.error = st.broken ? rel(r.measured, r.expected) : 1.0;
      });
}

namespace {
std::vector<double> weibull_samples(double shape, double mean) {
  const auto d = model::Distribution::weibull_from_mean(shape, mean);
  std::vector<double> x(100000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = d.sample(42, i, 3);
  return x;
}
}  // namespace

CaseResult a7_weibull_ks() {
  return timed(
      {"A7", "Weibull sampling (m = 3, N = 1e5): Kolmogorov-Smirnov D",
       "CDF 1 - exp(-(a/lam)^m), lam = a0 / Gamma(1 + 1/m); p > 0.01 <=> D < 1.628/sqrt(N)", 0, 0,
       0, 1.628 / std::sqrt(1e5), "counter-based stream"},
      [](CaseResult& r) {
        auto x = weibull_samples(3.0, 24.24e6);
        std::sort(x.begin(), x.end());
        const double lam = 24.24e6 / std::tgamma(1.0 + 1.0 / 3.0), n = double(x.size());
        double dmax = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
          const double f = 1.0 - std::exp(-std::pow(x[i] / lam, 3.0));
          dmax = std::max({dmax, f - double(i) / n, double(i + 1) / n - f});
        }
        r.error = r.measured = dmax;
      });
}

CaseResult a7_weibull_mean() {
  return timed({"A7", "Weibull sampling (m = 3, N = 1e5): mean", "a0", 24.24e6, 0, 0, 0.01,
                "counter-based stream"},
               [](CaseResult& r) {
                 const auto x = weibull_samples(3.0, 24.24e6);
                 double s = 0;
                 for (double v : x) s += v;
                 r.measured = s / double(x.size());
                 r.error = rel(r.measured, r.expected);
               });
}

namespace {
// One block on a spring with local damping alpha: the worst amplitude ratio per cycle (A8).
struct DampingRun {
  double worst_ratio, error, dt;
};

DampingRun damped_spring(double alpha, double safety) {
  model::Model m;
  m.rounding_length = 0.01 * a;
  model::add_block(m, square(0, a, a), rho, Group::specimen);
  model::add_block(m, square(0, 0, a), rho, Group::bottom_platen);
  solver::SolverSettings s;
  s.local_damping = alpha;
  s.safety_factor = safety;
  auto solver = make_solver(m, "linear_elastic", params({{"jkn", 1e10}, {"jks", 1e10}}), s);
  m.blocks.vy[0] = 0.01;
  const double y0 = m.blocks.y[0], expected = (1 - alpha) / (1 + alpha);
  std::vector<double> peaks;
  double u2 = 0, u1 = 0;
  while (peaks.size() < 6 && solver->steps() < 1000000) {
    solver->step();
    const double u = m.blocks.y[0] - y0;
    if (u1 > u2 && u1 >= u && u1 > 0) peaks.push_back(u1);
    u2 = u1;
    u1 = u;
  }
  DampingRun r{0, peaks.size() < 6 ? 1.0 : 0.0, solver->dt()};
  for (std::size_t i = 1; i < peaks.size(); ++i) {
    const double e = rel(peaks[i] / peaks[i - 1], expected);
    if (e >= r.error) {
      r.error = e;
      r.worst_ratio = peaks[i] / peaks[i - 1];
    }
  }
  return r;
}
}  // namespace

CaseResult a8_local_damping() {
  const double alpha = 0.1;
  return timed({"A8", "one block on a spring, local damping alpha = 0.1: amplitude ratio per cycle",
                "sqrt(energy ratio) = (1 - alpha)/(1 + alpha)", (1 - alpha) / (1 + alpha), 0, 0,
                0.02, "safety factor 0.05; worst of 5 cycles"},
               [&](CaseResult& r) {
                 const DampingRun d = damped_spring(alpha, 0.05);
                 r.measured = d.worst_ratio;
                 r.error = d.error;
               });
}

std::vector<Ladder> analytic_ladders() {
  Ladder period{"A3 bonded pair: period against time step",
                "time step (s), safety factor 0.8 ... 0.05",
                "period (s)",
                "exact T = 2 pi sqrt(m_eff / (jkn L))",
                0,
                {}};
  Ladder damping{"A8 local damping alpha = 0.1: amplitude ratio against time step",
                 "time step (s), safety factor 0.8 ... 0.05",
                 "amplitude ratio per cycle (worst of 5)",
                 "exact (1 - alpha)/(1 + alpha)",
                 0.9 / 1.1,
                 {}};
  for (double sf : {0.8, 0.4, 0.2, 0.1, 0.05}) {
    auto t0 = std::chrono::steady_clock::now();
    const PairRun p = bonded_pair(sf);
    const auto since = [](auto t) {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    period.reference_value = p.period_expected;
    period.rungs.push_back(
        {p.dt, p.period_measured, rel(p.period_measured, p.period_expected), since(t0), sf == 0.8});
    t0 = std::chrono::steady_clock::now();
    const DampingRun d = damped_spring(0.1, sf);
    damping.rungs.push_back({d.dt, d.worst_ratio, d.error, since(t0), sf == 0.8});
  }
  std::vector<Ladder> out{period, damping};
  for (Ladder& l : a10_ladders()) out.push_back(std::move(l));
  out.push_back(a11_frozen_ladder());
  return out;
}

std::vector<NamedCase> analytic_cases() {
  return {{"A1", a1_mass_properties},
          {"A2", a2_tessellation_area},
          {"A3", a3_bonded_pair_period},
          {"A3", a3_bonded_pair_energy_drift},
          {"A4", [] { return a4_incline(20); }},
          {"A4", [] { return a4_incline(40); }},
          {"A4", [] { return a4_incline(50); }},
          {"A5", a5_direct_shear_peak},
          {"A5", a5_direct_shear_residual},
          {"A5", a5_dilation},
          {"A6", a6_direct_tension},
          {"A7", a7_weibull_ks},
          {"A7", a7_weibull_mean},
          {"A8", a8_local_damping},
          {"A10", [] { return a10_burgers_creep(false); }},
          {"A10", [] { return a10_burgers_creep(true); }},
          {"A11", [] { return a11_stress_corrosion(false, 0.7, 4); }},
          {"A11", [] { return a11_stress_corrosion(true, 0.7, 4); }},
          {"A11", [] { return a11_stress_corrosion(false, 0.3, 4); }},
          {"A13", a13_patch_test}};
}

}  // namespace vorodec::verification
