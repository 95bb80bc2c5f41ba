#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cases.hpp"
#include "scenes.hpp"
#include "vorodec/model/zoning.hpp"

namespace vorodec::verification {

using model::Group;

namespace {

constexpr double rho = 2600, E = 30e9, nu = 0.25;  // kg/m^3, Pa, plane strain

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Mean y displacement of the gridpoints that start at height y (boundary rows of a column).
double mean_uy_at(const model::Zoning& z, double y) {
  double s = 0;
  int n = 0;
  for (std::size_t g = 0; g < z.gridpoints(); ++g)
    if (std::abs(z.y0[g] - y) < 1e-9) {
      s += z.y[g] - z.y0[g];
      ++n;
    }
  return s / n;
}

// Steps until the kinetic energy has fallen below `fraction` of its peak (at least `min_steps`).
void relax(solver::Solver& s, long min_steps, long max_steps, double fraction) {
  double peak = 0;
  for (long i = 0; i < max_steps; ++i) {
    s.step();
    const double ke = s.kinetic_energy();
    peak = std::max(peak, ke);
    if (i >= min_steps && ke <= fraction * peak) return;
  }
}

}  // namespace

CaseResult a13_patch_test() {
  CaseResult r{"A13",
               "patch test: deformable pentagon, boundary gridpoints at a uniform strain, "
               "interior relaxed",
               "sigma = D eps (plane strain, E 30 GPa, nu 0.25), every zone",
               0,
               0,
               0,
               1e-9,
               "zone size 0.02 m in a 0.1 m block, damping 0.8"};
  const auto t0 = std::chrono::steady_clock::now();
  model::Model m;
  m.rounding_length = 5e-4;
  const std::vector<model::Point> poly{{0, 0}, {0.1, 0}, {0.13, 0.06}, {0.05, 0.11}, {-0.02, 0.05}};
  model::add_deformable_block(m, poly, rho, {E, nu}, 0.02, Group::specimen);
  auto& z = m.zoning;
  const double exx = 2e-4, eyy = -1e-4, gxy = 1.5e-4;  // engineering shear strain
  for (std::size_t k = 0; k < z.corner_gp.size(); ++k) {
    const auto g = static_cast<std::size_t>(z.corner_gp[k]);
    z.prescribed[g] = 1;
    z.x[g] = z.x0[g] + exx * z.x0[g] + 0.5 * gxy * z.y0[g];
    z.y[g] = z.y0[g] + 0.5 * gxy * z.x0[g] + eyy * z.y0[g];
  }
  solver::SolverSettings s;
  auto solver = make_solver(m, "linear_elastic", params({{"jkn", 1e12}, {"jks", 1e12}}), s);
  relax(*solver, 2000, 200000, 1e-20);
  const model::ElasticMaterial mat{E, nu};
  const double l = mat.lambda(), G = mat.shear_modulus();
  const double sxx = (l + 2 * G) * exx + l * eyy, syy = l * exx + (l + 2 * G) * eyy, sxy = G * gxy;
  const double scale = std::max({std::abs(sxx), std::abs(syy), std::abs(sxy)});
  double worst = 0;
  for (std::size_t i = 0; i < z.zones.size(); ++i) {
    const model::ZoneStress st = z.stress(i);
    worst = std::max({worst, std::abs(st.xx - sxx), std::abs(st.yy - syy), std::abs(st.xy - sxy),
                      std::abs(st.zz - nu * (sxx + syy))});
  }
  r.expected = sxx;
  r.measured = z.stress(0).xx;
  r.error = worst / scale;
  r.settings += fmt::format(", {} zones, {} steps", z.zones.size(), solver->steps());
  r.seconds = seconds_since(t0);
  return r;
}

std::vector<CaseResult> deformable_column(double h) {
  constexpr double W = 0.05, H = 0.2, g = 9.81;  // m, m, m/s^2
  const model::ElasticMaterial mat{E, nu};
  const double e_plane = E / (1 - nu * nu);  // uniaxial stress in plane strain
  const auto column = [&](bool top_platen) {
    auto m = std::make_unique<model::Model>();
    m->rounding_length = 2e-4;
    model::add_deformable_block(*m, {{0, 0}, {W, 0}, {W, H}, {0, H}}, rho, mat, h, Group::specimen);
    const auto slab = [&](double y0, double y1) {
      return std::vector<model::Point>{{-W, y0}, {2 * W, y0}, {2 * W, y1}, {-W, y1}};
    };
    model::add_block(*m, slab(-0.02, 0), rho, Group::bottom_platen);
    if (top_platen) model::add_block(*m, slab(H, H + 0.02), rho, Group::top_platen);
    return m;
  };
  // Frictionless platens, joints 10x stiffer than the zones (docs/theory.md §4.4: (K + 4G/3)/dz).
  const double jkn = 10 * (mat.lambda() + 2 * mat.shear_modulus()) / h;
  const auto law = params({{"jkn", jkn},
                           {"jks", 0},
                           {"friction", 0},
                           {"tension", 0},
                           {"cohesion", 0},
                           {"dilation", 0}});
  const auto rel = [](double measured, double expected) {
    return std::abs(measured - expected) / std::abs(expected);
  };
  std::vector<CaseResult> out;
  {
    const auto t0 = std::chrono::steady_clock::now();
    auto m = column(false);
    solver::SolverSettings s;
    s.gravity = {0, -g};
    auto solver = make_solver(*m, "mohr_coulomb", law, s);
    relax(*solver, 2000, 400000, 1e-10);
    const auto& z = m->zoning;
    const double shortening = mean_uy_at(z, 0) - mean_uy_at(z, H);
    const double exact = rho * g * H * H / (2 * e_plane);
    // Zone sigma_yy: area-weighted over the band of zones whose centroids lie within half a zone
    // size of mid-height (the exact mean there is the exact value at the band's centroid), and
    // the largest single-zone error relative to the base stress rho g H.
    double worst = 0, band_area = 0, band_stress = 0, band_y = 0;
    for (std::size_t i = 0; i < z.zones.size(); ++i) {
      double yc = 0;
      for (auto k : z.zones[i].gp) yc += z.y0[k] / 3;
      worst = std::max(worst, std::abs(z.stress(i).yy + rho * g * (H - yc)));
      if (std::abs(yc - 0.5 * H) > 0.5 * h) continue;
      band_area += z.zones[i].area;
      band_stress += z.zones[i].area * z.stress(i).yy;
      band_y += z.zones[i].area * yc;
    }
    band_stress /= band_area;
    const double band_exact = -rho * g * (H - band_y / band_area);
    const double reaction = -solver->contact_force(1).y;  // the column pushes the platen down
    const double weight = rho * W * H * g;
    const double secs = seconds_since(t0);
    const std::string set = fmt::format("{} zones (size {} m), {} steps, damping 0.8",
                                        z.zones.size(), h, solver->steps());
    out.push_back({"A13", "deformable column 0.05 x 0.2 m on a platen, own weight: shortening",
                   "rho g H^2 (1 - nu^2) / (2 E)", exact, shortening, rel(shortening, exact), 0.01,
                   set, secs});
    out.push_back({"A13", "same column: mean zone sigma_yy in a band at mid-height",
                   "-rho g (H - y) at the band's centroid", band_exact, band_stress,
                   rel(band_stress, band_exact), 0.01, set, secs});
    CaseResult zone{"A13",
                    "same column: largest single-zone sigma_yy error / rho g H (constant-strain "
                    "zones in a linear stress field)",
                    "-rho g (H - y_centroid)",
                    0,
                    worst / (rho * g * H),
                    worst / (rho * g * H),
                    0,
                    set,
                    secs};
    zone.informational = true;
    out.push_back(zone);
    out.push_back({"A13", "same column: platen reaction = weight", "rho g W H", weight, reaction,
                   rel(reaction, weight), 1e-3, set, secs});
  }
  {
    const auto t0 = std::chrono::steady_clock::now();
    auto m = column(true);
    solver::SolverSettings s;
    auto solver = make_solver(*m, "mohr_coulomb", law, s);
    // Press the top platen down by 0.01 % of the height, then hold it.
    const double v = 1e-2, target = m->blocks.y0[2] - 1e-4 * H;
    while (m->blocks.y[2] > target) {
      m->blocks.vy[2] = -std::min(v, (m->blocks.y[2] - target) / solver->dt());
      solver->step();
    }
    m->blocks.vy[2] = 0;
    relax(*solver, 2000, 400000, 1e-10);
    const auto& z = m->zoning;
    const double eps = (mean_uy_at(z, H) - mean_uy_at(z, 0)) / H;  // negative: shortening
    const double stress = solver->contact_force(2).y / W;          // compression on the platen
    double ux_left = 0, ux_right = 0;
    int nl = 0, nr = 0;
    for (std::size_t k = 0; k < z.gridpoints(); ++k) {
      if (std::abs(z.x0[k]) < 1e-12) ux_left += z.x[k] - z.x0[k], ++nl;
      if (std::abs(z.x0[k] - W) < 1e-12) ux_right += z.x[k] - z.x0[k], ++nr;
    }
    const double lateral = (ux_right / nr - ux_left / nl) / W;
    const double secs = seconds_since(t0);
    const std::string set = fmt::format("{} zones (size {} m), {} steps, damping 0.8",
                                        z.zones.size(), h, solver->steps());
    out.push_back({"A13", "column between frictionless platens, uniaxial stress: sigma = E' eps",
                   "E' = E / (1 - nu^2), eps from the gridpoints", -e_plane * eps, stress,
                   rel(stress, -e_plane * eps), 0.01, set, secs});
    const double lateral_exact = -nu / (1 - nu) * eps;
    out.push_back({"A13", "same column: lateral strain", "eps_x = -nu / (1 - nu) eps_y",
                   lateral_exact, lateral, rel(lateral, lateral_exact), 0.01, set, secs});
  }
  return out;
}

CaseResult deformable_joint(double h, double rounding) {
  constexpr double W = 0.05, H = 0.1;  // m: two 0.05 x 0.05 blocks, one above the other
  const model::ElasticMaterial mat{E, nu};
  const double jkn = E / (1 - nu * nu) / 0.01;  // Pa/m: the joint as compliant as 1 cm of rock
  const auto t0 = std::chrono::steady_clock::now();
  model::Model m;
  m.rounding_length = rounding;
  const auto rect = [](double x0, double y0, double x1, double y1) {
    return std::vector<model::Point>{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  };
  model::add_deformable_block(m, rect(0, 0, W, H / 2), rho, mat, h, Group::specimen);
  model::add_deformable_block(m, rect(0, H / 2, W, H), rho, mat, h, Group::specimen);
  model::add_block(m, rect(-W, -0.02, 2 * W, 0), rho, Group::bottom_platen);
  model::add_block(m, rect(-W, H, 2 * W, H + 0.02), rho, Group::top_platen);
  // The joint: elastic in both directions (no lateral drift of one block on the other); the
  // platens: frictionless (uniaxial stress).
  std::vector<std::unique_ptr<laws::LawGroup>> groups;
  groups.push_back(laws::find_law("linear_elastic")->make(params({{"jkn", jkn}, {"jks", jkn}}), 7));
  groups.push_back(laws::find_law("mohr_coulomb")
                       ->make(params({{"jkn", jkn},
                                      {"jks", 0},
                                      {"friction", 0},
                                      {"tension", 0},
                                      {"cohesion", 0},
                                      {"dilation", 0}}),
                              7));
  solver::LawTable table;
  const auto specimen = static_cast<std::size_t>(Group::specimen);
  table.law[specimen][specimen] = 0;
  for (const Group platen : {Group::bottom_platen, Group::top_platen}) {
    table.law[specimen][static_cast<std::size_t>(platen)] = 1;
    table.law[static_cast<std::size_t>(platen)][specimen] = 1;
  }
  solver::SolverSettings s;
  s.contact_tolerance = rounding;
  auto solver = std::make_unique<solver::Solver>(m, std::move(groups), table, s);
  solver->initialise();
  const std::size_t top = 3;
  const double target = m.blocks.y0[top] - 1e-4 * H;
  while (m.blocks.y[top] > target) {
    m.blocks.vy[top] = -std::min(1e-2, (m.blocks.y[top] - target) / solver->dt());
    solver->step();
  }
  m.blocks.vy[top] = 0;
  relax(*solver, 2000, 400000, 1e-12);
  const auto& z = m.zoning;
  // The jump across the joint: the top block's lowest gridpoints against the bottom block's
  // highest (both start at H / 2).
  double below = 0, above = 0;
  int nb = 0, na = 0;
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    if (std::abs(z.y0[g] - H / 2) > 1e-9) continue;
    (z.block[g] == 0 ? below : above) += z.y[g] - z.y0[g];
    ++(z.block[g] == 0 ? nb : na);
  }
  const double closure = below / nb - above / na;  // > 0: the joint closes
  const double stress = solver->contact_force(top).y / W;
  CaseResult r{"A13",
               "two deformable blocks across a straight joint, uniaxial stress: joint stiffness "
               "sigma / closure",
               "jkn (the joint law's normal stiffness)",
               jkn,
               stress / closure,
               0,
               0.01,
               fmt::format("zone size {} m, rounding {} m, {} zones, {} steps", h, rounding,
                           z.zones.size(), solver->steps()),
               seconds_since(t0)};
  r.error = std::abs(r.measured - r.expected) / r.expected;
  return r;
}

std::vector<Ladder> deformable_joint_ladders() {
  std::vector<Ladder> out;
  for (const double d : {2e-4, 1e-3}) {
    Ladder l{fmt::format("A13 joint between zoned blocks, rounding length {:g} m: "
                         "sigma / closure against the zone size",
                         d),
             "zone size (m); no default (zone_size is required)",
             "joint stiffness (Pa/m)",
             "exact: jkn",
             0,
             {}};
    for (const double h : {0.05, 0.025, 0.0125, 0.00625, 0.003125, 0.0015625}) {
      const CaseResult r = deformable_joint(h, d);
      l.reference_value = r.expected;
      l.rungs.push_back({h, r.measured, r.error, r.seconds, false});
    }
    out.push_back(l);
  }
  return out;
}

}  // namespace vorodec::verification
