// Waves and quiet boundaries (docs/theory.md §15): P-wave speed in a row of rigid
// blocks and in a Voronoi bar, and the energy a quiet boundary reflects.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "cases.hpp"
#include "scenes.hpp"
#include "vorodec/geometry/tessellation.hpp"
#include "vorodec/loading/quiet_boundary.hpp"
#include "vorodec/solver/elastic_response.hpp"

namespace vorodec::verification {

namespace {

constexpr double rho = 2600, d = 1e-3, jkn = 1e13;  // kg/m^3, m, Pa/m: c = sqrt(jkn d / rho)
const double c_row = std::sqrt(jkn * d / rho);

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Time of the largest value of a sampled series, refined by a parabola through its neighbours.
double peak_time(const std::vector<double>& t, const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::size_t k = 0;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i] > v[k]) k = i;
  if (k == 0 || k + 1 >= v.size()) return t[k];
  const double a = v[k - 1], b = v[k], c = v[k + 1], h = t[k + 1] - t[k];
  return t[k] + 0.5 * h * (a - c) / (a - 2 * b + c);
}

// A half-sine particle velocity v0 sin(pi t / T) for t < T.
loading::InputHistory half_sine(double v0, double duration) {
  return [=](double t) {
    return loading::InputVelocity{t < duration ? v0 * std::sin(std::numbers::pi * t / duration) : 0,
                                  0.0};
  };
}

struct RowRun {
  std::vector<double> t;
  std::vector<std::vector<double>> v;  // per station
  double dt = 0;
};

// `blocks` squares of side d in a row, bonded elastic, undamped; a pulse `wavelength` m long
// (c times its duration) enters through a quiet left end; the right end is quiet (or free:
// `quiet_end` false). Records vx at `stations` (block indices) for `duration` s, or for `steps`
// steps if given; `snapshot` (if not null) gets every block's vx at its end, `energy` (if not
// null) the kinetic plus contact strain energy after every step.
RowRun row_run(int blocks, double wavelength, bool quiet_end, const std::vector<int>& stations,
               double duration, std::vector<double>* snapshot = nullptr, long steps = 0,
               std::vector<double>* energy = nullptr) {
  model::Model m;
  m.rounding_length = 0.01 * d;
  for (int i = 0; i < blocks; ++i)
    model::add_block(m, square(i * d, 0, d), rho, model::Group::specimen);
  solver::SolverSettings s;
  s.local_damping = 0.0;
  auto solver = make_solver(m, "linear_elastic", params({{"jkn", jkn}, {"jks", jkn}}), s);
  const auto edge = [&](int b, std::uint32_t k) {
    return loading::BoundaryEdge{static_cast<std::uint32_t>(b),
                                 m.blocks.corner_begin[static_cast<std::size_t>(b)] + k};
  };
  // Square corners counter-clockwise from the lower left: edge 1 is the right side, 3 the left.
  loading::QuietBoundary quiet(
      quiet_end ? std::vector{edge(blocks - 1, 1)} : std::vector<loading::BoundaryEdge>{},
      {rho, c_row, c_row});
  const double v0 = 1e-3;
  quiet.set_input({edge(0, 3)}, half_sine(v0, wavelength / c_row));
  RowRun r;
  r.dt = solver->dt();
  r.v.resize(stations.size());
  while (steps > 0 ? solver->steps() < steps : solver->time() < duration) {
    quiet.clear_loads(m);
    quiet.apply(m, solver->time());
    solver->step();
    r.t.push_back(solver->time());
    for (std::size_t k = 0; k < stations.size(); ++k)
      r.v[k].push_back(m.blocks.vx[static_cast<std::size_t>(stations[k])] / v0);
    if (energy) energy->push_back(solver->kinetic_energy() + solver->contact_strain_energy());
  }
  if (snapshot) *snapshot = m.blocks.vx;
  return r;
}

}  // namespace

std::vector<CaseResult> a9_row_of_blocks() {
  std::vector<CaseResult> rows;
  const int blocks = 400;
  const double x1 = 100 * d, x2 = 300 * d;
  for (const double lambda_blocks : {40.0, 20.0, 10.0, 5.0}) {
    const auto t0 = std::chrono::steady_clock::now();
    const double lambda = lambda_blocks * d;
    const RowRun r = row_run(blocks, lambda, true, {100, 300}, (x2 + lambda) / c_row * 1.05);
    const double speed = (x2 - x1) / (peak_time(r.t, r.v[1]) - peak_time(r.t, r.v[0]));
    CaseResult c{"A9",
                 fmt::format("P wave in a row of 400 rigid blocks, half-sine pulse {:g} blocks "
                             "long: speed of its peak",
                             lambda_blocks),
                 "c = sqrt(jkn d / rho) (E_eff = jkn d)",
                 c_row,
                 speed,
                 std::abs(speed / c_row - 1.0),
                 0.02,
                 fmt::format("d 1 mm, jkn 1e13 Pa/m, no damping, dt {:.3g} s, quiet ends", r.dt)};
    // Shorter than 20 blocks the chain's dispersion (group velocity c cos(k d / 2)) shows:
    // reported.
    c.informational = lambda_blocks < 20;
    c.seconds = seconds_since(t0);
    rows.push_back(c);
    if (lambda_blocks == 20) {
      double peak = 0;
      for (const double v : r.v[0]) peak = std::max(peak, v);
      CaseResult in{"A9",
                    "input through the quiet end: incident particle velocity / v_in",
                    "sigma = 2 rho c v_in on a dashpot rho c gives v = v_in (docs/theory.md §15.2)",
                    1.0,
                    peak,
                    std::abs(peak - 1.0),
                    0.02,
                    "wavelength 20 blocks, at block 100"};
      in.seconds = c.seconds;
      rows.push_back(in);
    }
  }
  return rows;
}

std::vector<CaseResult> quiet_boundary_absorption() {
  std::vector<CaseResult> rows;
  // The reflected wave is the difference between the row with its end at block 400 and a row
  // long enough that nothing has come back, over the last 100 blocks, once the pulse has passed
  // the end: the row is linear, so the difference is the reflection alone. Its energy is twice
  // its kinetic energy (a travelling wave), against the incident pulse's.
  for (const bool quiet : {true, false}) {
    const auto t0 = std::chrono::steady_clock::now();
    const double lambda = 20 * d, duration = (400 * d + lambda + 50 * d) / c_row;
    std::vector<double> end_row, long_row;
    const RowRun a = row_run(400, lambda, quiet, {200}, duration, &end_row);
    row_run(800, lambda, true, {200}, duration, &long_row);
    const double m = rho * d * d;
    double reflected = 0;
    for (int i = 300; i < 400; ++i) {
      const double dv =
          end_row[static_cast<std::size_t>(i)] - long_row[static_cast<std::size_t>(i)];
      reflected += m * dv * dv;
    }
    // Incident: twice the kinetic energy the pulse carried past block 200, from its history.
    double incident = 0;
    for (const double v : a.v[0]) incident += v * v;
    incident *= (1e-3 * 1e-3) * m * c_row * a.dt / d;  // sum over the pulse's length
    const double ratio = reflected / incident;
    CaseResult c{"A9",
                 quiet ? "quiet end (dashpot rho c per unit area), normal incidence: reflected "
                         "energy / incident"
                       : "free end, normal incidence (contrast): reflected energy / incident",
                 quiet ? "Lysmer-Kuhlemeyer: no reflection of a normally incident P wave"
                       : "a free end reflects everything",
                 quiet ? 0.0 : 1.0,
                 ratio,
                 quiet ? ratio : std::abs(ratio - 1.0),
                 quiet ? 0.02 : 0.05,
                 "row of 400 blocks, half-sine pulse of 20 blocks, against an 800-block row"};
    c.seconds = seconds_since(t0);
    rows.push_back(c);
  }
  return rows;
}

CaseResult quiet_row_long_run(long steps) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> energy;
  const RowRun r = row_run(400, 20 * d, true, {200}, 0, nullptr, steps, &energy);
  // The pulse has left through the right end after one transit and its length; from twice that
  // on, the energy left in the row must stay small and must not grow.
  const auto after = static_cast<std::size_t>(2 * (400 * d + 20 * d) / c_row / r.dt);
  double peak = 0, later = 0;
  for (std::size_t i = 0; i < energy.size(); ++i) {
    if (i < after)
      peak = std::max(peak, energy[i]);
    else
      later = std::max(later, energy[i]);
  }
  CaseResult c{"A9",
               fmt::format("zero damping, quiet ends, {:g} steps: largest energy in the row after "
                           "the pulse left / its largest before",
                           static_cast<double>(steps)),
               "bounded: the quiet ends take the pulse out and nothing grows",
               0.0,
               later / peak,
               later / peak,
               0.01,
               "row of 400 blocks, half-sine pulse of 20 blocks"};
  c.seconds = seconds_since(t0);
  return c;
}

std::vector<CaseResult> a9_voronoi_bar() {
  const auto t0 = std::chrono::steady_clock::now();
  // The marble's blocks and contacts (models/ucs_marble.toml, strengths out of reach) in a
  // 20 x 200 mm bar along y.
  const double w = 0.02, h = 0.2, density = 2602;
  geometry::TessellationSettings ts;
  ts.outline = {geometry::OutlineKind::rectangle, w, h, 0, 0};
  ts.block_count = 1042;  // the marble's block size: 1302 blocks in 50 x 100 mm
  ts.seed = 42;
  ts.lloyd_iterations = 2;
  ts.min_edge_length = 2.5e-4;
  const geometry::Tessellation tess = geometry::tessellate(ts);
  const laws::LawParams marble = params({{"jkn", 1.77e13},
                                         {"jks", 6.7e12},
                                         {"tension", 1e12},
                                         {"cohesion", 1e12},
                                         {"friction", 10},
                                         {"dilation", 0},
                                         {"residual_friction", 10}});
  // E_eff: the bar's static modulus, from the implicit elastic response to a platen's unit
  // displacement (platens bonded: their restraint of the ends stiffens the bar a little).
  double modulus = 0;
  {
    model::Model m = model::build_model(tess, {density, 1e-4, true});
    auto solver = make_solver(m, "mohr_coulomb", marble, {});
    std::vector<std::array<double, 3>> unit(m.blocks.size(), {0, 0, 0}), load = unit;
    std::size_t top = 0;
    for (std::size_t b = 0; b < m.blocks.size(); ++b) {
      if (m.blocks.group[b] == model::Group::specimen) continue;
      m.blocks.prescribed[b] = 1;
      if (m.blocks.group[b] == model::Group::top_platen) top = b;
    }
    unit[top] = {0, -1, 0};
    const solver::ElasticResponse r = solver::elastic_response(m, solver->laws(), unit, load, 0);
    modulus = std::abs(r.unit.force[top][1]) / w * h;  // Pa: (F / w) / (1 m / h)
  }
  model::Model m = model::build_model(tess, {density, 1e-4, false});
  solver::SolverSettings s;
  s.local_damping = 0.0;
  auto solver = make_solver(m, "mohr_coulomb", marble, s);
  // A pulse five bar widths long. At 40 mm the peak travelled 3.5 % slower than c (measured);
  // Rayleigh's correction for a strip, (nu pi w / lambda)^2 / 12, explains 1.1 % of it, the rest
  // (scattering by the blocks?) is not established.
  const double c = std::sqrt(modulus / density), lambda = 0.1, v0 = 1e-3;
  loading::QuietBoundary quiet(loading::outline_edges(m, loading::Side::top), {density, c, c});
  quiet.set_input(loading::outline_edges(m, loading::Side::bottom), [=](double t) {
    return loading::InputVelocity{
        t < lambda / c ? v0 * std::sin(std::numbers::pi * t * c / lambda) : 0.0, 0.0};
  });
  // Stations: the mean vy of the blocks within 2 mm of y = 50 and 150 mm.
  const double y1 = 0.05, y2 = 0.15;
  std::vector<double> t, v1, v2;
  while (solver->time() < (y2 + lambda) / c * 1.1) {
    quiet.clear_loads(m);
    quiet.apply(m, solver->time());
    solver->step();
    double s1 = 0, s2 = 0;
    int n1 = 0, n2 = 0;
    for (std::size_t b = 0; b < m.blocks.size(); ++b) {
      if (std::abs(m.blocks.y0[b] - y1) < 2e-3) {
        s1 += m.blocks.vy[b];
        ++n1;
      }
      if (std::abs(m.blocks.y0[b] - y2) < 2e-3) {
        s2 += m.blocks.vy[b];
        ++n2;
      }
    }
    t.push_back(solver->time());
    v1.push_back(s1 / n1);
    v2.push_back(s2 / n2);
  }
  const double speed = (y2 - y1) / (peak_time(t, v2) - peak_time(t, v1));
  CaseResult r{
      "A9",
      "P wave in a Voronoi bar (the marble's 2 mm blocks and contacts, 20 x 200 mm), "
      "half-sine pulse of 100 mm: speed of its peak",
      fmt::format("c = sqrt(E_eff / rho), E_eff = {:.4g} GPa the bar's static modulus "
                  "(implicit elastic response)",
                  modulus / 1e9),
      c,
      speed,
      std::abs(speed / c - 1.0),
      0.02,
      fmt::format("{} blocks, no damping, dt {:.3g} s, quiet top", m.blocks.size(), solver->dt())};
  r.seconds = seconds_since(t0);
  return {r};
}

}  // namespace vorodec::verification
