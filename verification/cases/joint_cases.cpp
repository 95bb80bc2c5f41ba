// R2: one Barton-Bandis contact in direct shear under a constant normal stress, and in normal
// closure (docs/theory.md §6.6). The normal stress is held by moving the gap each step.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include "cases.hpp"
#include "model_runs.hpp"
#include "scenes.hpp"
#include "vorodec/geometry/joints.hpp"
#include "vorodec/laws/barton_bandis.hpp"

namespace vorodec::verification {

namespace {

using laws::BartonBandis;

// A rough granite joint: JRC 10, JCS 100 MPa, phi_r 30 deg [Barton1977]; kni 20 GPa/m and
// vm 0.5 mm [Bandis1983]; 0.1 m of joint per contact.
constexpr double L = 0.1;
BartonBandis::Props rough_joint() {
  return {20e9, 0.5e-3, 2e9, 10.0, 100e6, 30.0, 100e6, L};
}

double barton_peak(double sn) {  // Pa, Barton-Choubey with the 70 deg ceiling
  const double deg = std::min(10.0 * std::log10(100e6 / sn) + 30.0, 70.0);
  return sn * std::tan(deg * M_PI / 180.0);
}

struct ShearRun {
  double peak;          // Pa
  double last;          // Pa, after `slide` of shear displacement
  double dilation_tan;  // opening / plastic slip in the first sliding steps after the peak
};

// Shears the contact by `slide` in steps of `du` at constant normal stress sn.
ShearRun shear_at(double sn, double slide, double du) {
  const auto p = rough_joint();
  BartonBandis::State st{0.0, 0.0, 0.0, 0.0};
  ShearRun out{0, 0, 0};
  double opening = 0, plastic = 0;
  int sliding_steps = 0;
  for (double s = 0; s < slide; s += du) {
    const double gap = st.u_dil - BartonBandis::closure_at(p, sn);
    const double fs_before = st.fs, u_before = st.u_dil;
    const auto r = BartonBandis::evaluate({gap, 0.0, -du, L, 1e-6}, p, st);
    out.peak = std::max(out.peak, std::abs(r.fs) / L);
    out.last = std::abs(r.fs) / L;
    if (r.event == laws::ContactEvent::slip && sliding_steps < 20) {
      ++sliding_steps;
      opening += st.u_dil - u_before;
      plastic += du - (st.fs - fs_before) / (p.ks * L);
    }
  }
  out.dilation_tan = opening / plastic;
  return out;
}

constexpr double stresses[] = {0.5e6, 1e6, 2e6, 5e6, 10e6, 20e6, 50e6};

}  // namespace

CaseResult r2_peak_strength() {
  return timed({"R2", "rough joint (JRC 10, JCS 100 MPa, phi_r 30 deg) in direct shear: peak",
                "tau_p = sn tan(JRC log10(JCS/sn) + phi_r) [Barton1977]; worst of sn = 0.5-50 MPa",
                0, 0, 0, 0.01, "shear steps 1 um, sn held"},
               [](CaseResult& r) {
                 const double ks = rough_joint().ks;
                 for (double sn : stresses) {
                   const double peak = shear_at(sn, 1.5 * barton_peak(sn) / ks, 1e-6).peak;
                   const double e = std::abs(peak / barton_peak(sn) - 1);
                   if (e >= r.error) r.measured = peak, r.expected = barton_peak(sn), r.error = e;
                 }
               });
}

CaseResult r2_residual_strength() {
  return timed({"R2", "rough joint: strength after 100 x the peak displacement",
                "tau_r = sn tan(phi_r) (mobilised JRC 0) [Barton1982]; worst of sn = 0.5-50 MPa", 0,
                0, 0, 0.01, "shear steps 10 um, sn held"},
               [](CaseResult& r) {
                 const auto p = rough_joint();
                 for (double sn : stresses) {
                   const double peak_slide = barton_peak(sn) / p.ks;
                   const double last = shear_at(sn, 101 * peak_slide, 1e-5).last;
                   const double residual = sn * std::tan(M_PI / 6);
                   const double e = std::abs(last / residual - 1);
                   if (e >= r.error) r.measured = last, r.expected = residual, r.error = e;
                 }
               });
}

CaseResult r2_dilation() {
  return timed({"R2", "rough joint: dilation at the peak, sn = 5 MPa",
                "tan(JRC log10(JCS/sn) / 2) [Barton1977]",
                std::tan(0.5 * 10 * std::log10(20.0) * M_PI / 180), 0, 0, 0.01,
                "opening / plastic slip over the first 20 sliding steps of 1 um"},
               [](CaseResult& r) {
                 r.measured = shear_at(5e6, 0.01, 1e-6).dilation_tan;
                 r.error = std::abs(r.measured / r.expected - 1);
               });
}

CaseResult r2_normal_closure() {
  return timed({"R2", "rough joint: normal closure up to 0.9 JCS, and its stored energy",
                "v = sn vm / (kni vm + sn) [Bandis1983]; energy = integral of sn dv (trapezoid "
                "over the closure steps)",
                0, 0, 0, 0.01, "closure steps vm / 2e5"},
               [](CaseResult& r) {
                 const auto p = rough_joint();
                 BartonBandis::State st{0.0, 0.0, 0.0, 0.0};
                 double work = 0, sn_prev = 0, worst = 0;
                 for (int i = 1; i <= 200000; ++i) {
                   const double v = p.vm * i / 2e5;
                   const double sn = BartonBandis::evaluate({-v, 0, 0, L, 1e-6}, p, st).fn / L;
                   if (sn > 0.9 * p.jcs) break;
                   work += 0.5 * (sn + sn_prev) * p.vm / 2e5 * L;
                   sn_prev = sn;
                   if (sn > 0.01 * p.jcs) {
                     const double expected = sn * p.vm / (p.kni * p.vm + sn);
                     worst = std::max(worst, std::abs(v / expected - 1));
                   }
                 }
                 const double energy = BartonBandis::strain_energy(p, sn_prev * L, 0.0);
                 r.expected = work;
                 r.measured = energy;
                 r.error = std::max(worst, std::abs(energy / work - 1));
               });
}

CaseResult j0_joint_length(double dip_deg) {
  return timed(
      {"J0",
       fmt::format("one persistent joint dipping {:g} deg through a 50 x 100 mm Voronoi specimen "
                   "(1302 blocks): length of the block pairs it separates",
                   dip_deg),
       "chord of the line across the rectangle", 0, 0, 0, 1e-3,
       "vertices within 0.2 x the mean block edge snapped onto the joint"},
      [&](CaseResult& r) {
        geometry::TessellationSettings s;
        s.outline = {geometry::OutlineKind::rectangle, 0.05, 0.1, 0, 0};
        s.block_count = 1302;
        s.seed = 42;
        s.lloyd_iterations = 2;
        s.min_edge_length = 2.5e-4;
        const auto intact = geometry::tessellate(s);
        geometry::JointSetGeometry g;
        g.dip_deg = dip_deg;
        g.spacing = 1.0;
        g.origin = {0.025, 0.05};
        const auto traces = geometry::joint_set_traces(g, s.outline, 0, s.seed);
        const auto cut = geometry::cut_by_joints(intact, traces, s);
        for (const auto& j : cut.joint_edges) r.measured += j.length;
        const double t = std::tan(dip_deg * M_PI / 180);
        // The line y - 0.05 = t (x - 0.025) across [0, 0.05] x [0, 0.1].
        const double half_x = std::min(0.025, 0.05 / std::abs(t));
        r.expected = 2 * half_x * std::sqrt(1 + t * t);
        r.error = std::abs(r.measured / r.expected - 1);
      });
}

// J1: models/triaxial_jointed_marble.toml at joint dips 35-60 deg against Jaeger's single plane of
// weakness (clean joint: sigma_1 - sigma_3 = 2 sigma_3 tan(phi) / ((1 - tan(phi) cot(b)) sin(2b))).
std::vector<CaseResult> j1_single_plane_of_weakness(const std::string& source_dir,
                                                    const std::string& binary) {
  const std::filesystem::path model =
      std::filesystem::path(source_dir) / "models" / "triaxial_jointed_marble.toml";
  const double s3 = 5e6, tan_phi = std::tan(M_PI / 6);
  std::vector<CaseResult> rows;
  for (const double dip : {35.0, 40.0, 45.0, 50.0, 55.0, 60.0}) {
    const double b = dip * M_PI / 180;
    const double jaeger = 2 * s3 * tan_phi / ((1 - tan_phi / std::tan(b)) * std::sin(2 * b));
    const auto out =
        std::filesystem::temp_directory_path() / fmt::format("vorodec_j1_dip{:g}", dip);
    const ModelRun run =
        run_model(binary, model, out, fmt::format("--set joint_set[0].dip={:g}", dip));
    rows.push_back(relative(
        "J1",
        fmt::format("marble with one clean joint (phi_w 30 deg) dipping {:g} deg, sigma_3 5 MPa: "
                    "sigma_1 - sigma_3 at the peak",
                    dip),
        "Jaeger's single plane of weakness [Jaeger1960]", jaeger,
        json_number(run.summary, "peak_stress_Pa") - s3, 0.05,
        fmt::format("models/triaxial_jointed_marble.toml --set joint_set[0].dip={:g}; exit {}", dip,
                    run.exit_code),
        run.seconds));
  }
  return rows;
}

namespace {

// A symmetric roof wedge (apex up, half apex angle alpha, base 2 m at the opening) between two
// fixed abutments that clamp it: each moved into the wedge by `clamp` m. The joints are stiff in
// shear, so the clamp hardly relaxes as the wedge settles (with soft joints it does: the roof
// wedge's relaxation analysis in rock-engineering texts). Returns the wedge's
// drop (m) after `seconds` under gravity, and the clamping normal force per face (N per m) and
// weight (N per m) it started with.
struct WedgeRun {
  double drop, normal_force, weight;
};
WedgeRun roof_wedge(double alpha_deg, double friction_deg, double clamp, double seconds) {
  const double alpha = alpha_deg * M_PI / 180, half = 1.0, h = half / std::tan(alpha);
  const double far = 3.0, rho = 2600, g = 9.81;
  model::Model m;
  m.rounding_length = 1e-3;
  const double dx = clamp / std::cos(alpha);  // horizontal shift giving `clamp` normal overlap
  model::add_block(m, std::vector<model::Point>{{-half, 0}, {half, 0}, {0, h}}, rho,
                   model::Group::specimen);
  model::add_block(m,
                   std::vector<model::Point>{
                       {-half - far + dx, 0}, {-half + dx, 0}, {dx, h}, {-half - far + dx, h}},
                   rho, model::Group::bottom_platen);
  model::add_block(m,
                   std::vector<model::Point>{
                       {half - dx, 0}, {half + far - dx, 0}, {half + far - dx, h}, {-dx, h}},
                   rho, model::Group::top_platen);
  solver::SolverSettings s;
  s.local_damping = 0.8;
  s.safety_factor = 0.5;
  s.gravity = {0, -g};
  auto solver = make_solver(m, "mohr_coulomb",
                            params({{"jkn", 1e12},
                                    {"jks", 1e13},
                                    {"friction", friction_deg},
                                    {"tension", 0},
                                    {"cohesion", 0},
                                    {"dilation", 0},
                                    {"residual_friction", friction_deg}}),
                            s);
  const double y0 = m.blocks.y[0];
  solver->step();  // the clamping's contact forces
  double normal = 0;
  for (const auto& c : m.contacts) normal += c.fn;
  while (solver->time() < seconds) solver->step();
  return {y0 - m.blocks.y[0], 0.5 * normal, m.blocks.gravity_mass[0] * g};
}

}  // namespace

// R3: the wedge's limit friction angle from its starting clamp and weight,
// sin(phi - alpha) = W cos(phi) / (2 N) [vertical equilibrium with both faces at their friction
// limit], solved by bisection; the wedge run 1 deg either side of it must stay and fall.
std::vector<CaseResult> r3_roof_wedge() {
  const double alpha = 20, clamp = 2e-7, seconds = 0.3, fall = 1e-3;
  const auto t0 = std::chrono::steady_clock::now();
  const WedgeRun start = roof_wedge(alpha, 45, clamp, 0.0);
  double lo = alpha, hi = 89;
  for (int i = 0; i < 100; ++i) {
    const double phi = 0.5 * (lo + hi), r = phi * M_PI / 180;
    (std::sin(r - alpha * M_PI / 180) < start.weight * std::cos(r) / (2 * start.normal_force)
         ? lo
         : hi) = phi;
  }
  const double critical = 0.5 * (lo + hi);
  std::vector<CaseResult> rows;
  for (const double offset : {-1.0, 1.0}) {
    const WedgeRun run = roof_wedge(alpha, critical + offset, clamp, seconds);
    const bool falls = offset < 0;
    CaseResult r{"R3",
                 fmt::format("roof wedge, half apex angle {:g} deg, clamped by N = {:.3g} N/m per "
                             "face (W = {:.3g} N/m): friction {:.2f} deg {}",
                             alpha, start.normal_force, start.weight, critical + offset,
                             falls ? "(1 deg below the limit) falls" : "(1 deg above) stays"),
                 fmt::format("limit equilibrium: phi_crit = {:.2f} deg; judged by the drop after "
                             "{:g} s against {:g} m",
                             critical, seconds, fall),
                 falls ? 1.0 : 0.0,
                 run.drop > fall ? 1.0 : 0.0,
                 0,
                 0,
                 "local damping 0.8, jkn 1000 GPa/m, jks 10,000 GPa/m (stiff: the clamp relaxes by "
                 "about 4 % as the wedge settles), rounding 1 mm"};
    r.error = r.measured == r.expected ? 0.0 : 1.0;
    r.settings += fmt::format("; drop {:.3g} m", run.drop);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / 2;
    rows.push_back(r);
  }
  return rows;
}

std::vector<CaseResult> rock_cases(const std::string& source_dir, const std::string& binary) {
  std::vector<CaseResult> rows;
  // R1's zone-size ladder: sigma_theta's error against wall time (verification/r1_kirsch_ladder),
  // the finest the judged rows.
  std::vector<std::vector<CaseResult>> ladder;
  for (const double h : {0.2, 0.1, 0.05, 0.025}) ladder.push_back(r1_kirsch(h));
  {
    std::ofstream csv(std::filesystem::path(source_dir) / "verification" / "r1_kirsch_ladder.csv");
    const double order = std::log2(ladder[2][1].error / ladder[3][1].error);
    csv << "parameter,value,error,seconds,default,order\n";
    for (std::size_t k = 0; k < ladder.size(); ++k)
      csv << fmt::format("{},{},{},{:.3f},{},{:.3f}\n", 0.2 / (1 << k), ladder[k][1].error,
                         ladder[k][1].error, ladder[k][1].seconds, k + 1 == ladder.size() ? 1 : 0,
                         order);
  }
  const std::filesystem::path dir = std::filesystem::path(source_dir) / "verification";
  const std::string plot =
      fmt::format("/usr/bin/python3 {} {} {} 'R1 Kirsch: sigma_theta, zone size at the wall / a'",
                  (dir / "plot_cost_accuracy.py").string(), (dir / "r1_kirsch_ladder.csv").string(),
                  (dir / "r1_kirsch_ladder.png").string());
  if (std::system(plot.c_str()) != 0) fmt::print(stderr, "R1: the cost-accuracy plot failed\n");
  for (std::size_t k = 0; k + 1 < ladder.size(); ++k)
    for (CaseResult r : ladder[k]) {
      r.informational = true;  // the ladder's coarser rungs
      rows.push_back(r);
    }
  for (const CaseResult& r : ladder.back()) rows.push_back(r);
  // R5: the same hole dug out of the loaded plate by an excavation, at the finest rung.
  for (const CaseResult& r : r1_kirsch(0.025, true)) rows.push_back(r);
  for (CaseResult r :
       {r2_peak_strength(), r2_residual_strength(), r2_dilation(), r2_normal_closure()})
    rows.push_back(r);
  for (const double dip : {0.0, 30.0, 50.0, 60.0, 75.0, 90.0}) rows.push_back(j0_joint_length(dip));
  for (auto& r : r3_roof_wedge()) rows.push_back(std::move(r));
  for (auto& r : r4_in_situ_start(source_dir)) rows.push_back(std::move(r));
  for (auto& r : j1_single_plane_of_weakness(source_dir, binary)) rows.push_back(std::move(r));
  return rows;
}

}  // namespace vorodec::verification
