#pragma once
// Verification cases: each runs one scene against its analytic or published reference and
// returns what it measured. The unit tests assert on them; verification/run.sh reports them.
#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace vorodec::verification {

struct CaseResult {
  std::string id;         // A1, A3, B1 ...
  std::string name;       // what is checked
  std::string reference;  // formula or source
  double expected = 0;    // reference value
  double measured = 0;
  double error = 0;            // relative error |measured - expected| / |expected| (or as stated)
  double tolerance = 0;        // on `error`
  std::string settings;        // discretisation used
  double seconds = 0;          // wall time
  bool informational = false;  // a derived value with no published reference: reported, not judged
  bool pass() const { return informational || error <= tolerance; }
};

// Fills the wall time of a case computed by `body`.
template <class F>
CaseResult timed(CaseResult r, F body) {
  const auto t0 = std::chrono::steady_clock::now();
  body(r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

// Analytic cases (fast: part of the unit tests too).
CaseResult a1_mass_properties();
CaseResult a2_tessellation_area();
CaseResult a3_bonded_pair_period();
CaseResult a3_bonded_pair_energy_drift();
CaseResult a4_incline(double angle_deg);  // sticking: measured = displacement (m), expected 0
CaseResult a5_direct_shear_peak();
CaseResult a5_direct_shear_residual();
CaseResult a5_dilation();
CaseResult a6_direct_tension();
CaseResult a7_weibull_ks();
CaseResult a7_weibull_mean();
CaseResult a8_local_damping();

// R2: one Barton-Bandis contact (verification/cases/joint_cases.cpp, milliseconds).
CaseResult r2_peak_strength();
CaseResult r2_residual_strength();
CaseResult r2_dilation();
CaseResult r2_normal_closure();
// J0: a persistent joint through a Voronoi specimen: the length of the block pairs it separates
// against the line's chord (fast: part of the unit tests too).
CaseResult j0_joint_length(double dip_deg);
// R1: a circular hole in an elastic domain of four zoned blocks under Kirsch's boundary
// tractions: sigma_r, sigma_theta along the axes and the wall's radial displacement, at zone size
// h (m; the hole's radius is 1 m). dug (R5): the hole starts filled by a zoned plug under the far
// field, which an excavation removes; the wall's displacement is then measured from before.
std::vector<CaseResult> r1_kirsch(double h, bool dug = false);
// R3: a roof wedge clamped between two abutments under gravity, 1 deg of friction either side of
// its limit equilibrium (fast: part of the unit tests too): expected 1 = falls, 0 = stays.
std::vector<CaseResult> r3_roof_wedge();
// R4: the forces through cuts of a rock mass started under its in-situ stress.
std::vector<CaseResult> r4_in_situ_start(const std::string& source_dir);
// The rock-mass cases (R, J), run by `vorodec_verify --rock-only` into their own section.
std::vector<CaseResult> rock_cases(const std::string& source_dir, const std::string& binary);

// One Burger's contact held at a constant force (fast: part of the unit tests too).
CaseResult a10_burgers_creep(bool shear);

// One stress-corroding contact at stress ratio s (sigma / sigma_t0), forces held, stepped by the
// corrosion driver's clock with n_c (fast: part of the unit tests too): its time to failure (s)
// against the quadrature; infinity where it never fails.
double a11_quadrature(bool bonded_length, double s);
// frozen: [Potyondy2007]'s estimate and step, the rate frozen at the step's start.
double a11_stepped(bool bonded_length, double s, double n_c, bool frozen);
CaseResult a11_stress_corrosion(bool bonded_length, double s, double n_c);

// Deformable blocks (fast: part of the unit tests too).
CaseResult a13_patch_test();
// A deformable column on a rigid platen under its own weight, and between platens under uniaxial
// stress: stress and displacement against the plane-strain elastic solution.
std::vector<CaseResult> deformable_column(double zone_size);
// Two deformable blocks stacked across a straight joint between frictionless platens, pressed
// and relaxed: the joint's stress over its closure against jkn.
CaseResult deformable_joint(double zone_size, double rounding_length);

// A9 and quiet boundaries (verification/cases/wave_cases.cpp, seconds): the P-wave speed in a
// row of rigid blocks at four pulse wavelengths (dispersion below 20 blocks: reported), the input
// through a quiet end, the energy a quiet and a free end reflect, and the wave speed in a Voronoi
// bar against its static modulus.
std::vector<CaseResult> a9_row_of_blocks();
std::vector<CaseResult> quiet_boundary_absorption();
std::vector<CaseResult> a9_voronoi_bar();

// A12 (verification/cases/shpb_cases.cpp, in-process, milliseconds): the exact bars against the
// striker's analytic pulse, and full transmission from one bar to another.
std::vector<CaseResult> a12_exact_bar();
std::vector<CaseResult> a12_bar_on_bar();
// Bars built from blocks: the striker's pulse (models/shpb_granite.toml, square, 2 m/s), and the
// 10 m/s impact against the exact bars' and against the platens' contact forces.
std::vector<CaseResult> a12_block_bars(const std::string& source_dir, const std::string& binary,
                                       const std::filesystem::path& work);
// The row with quiet ends and no damping for `steps` steps after the pulse (1e6: about a minute).
CaseResult quiet_row_long_run(long steps);

// Published results: whole model runs (minutes), run by verification/run.sh only.
std::vector<CaseResult> b1_marble_ucs(const std::string& source_dir, const std::string& binary);
// C1: `vorodec calibrate models/calibrate_marble.toml` into `out` (about an hour on 2 cores; run
// again on the same folder, it replays): each target at the best evaluation, and the wall time.
// B1D: models/ucs_deformable_marble.toml against the paper and against the rigid marble; draws
// their stress-strain curves and crack maps to `figure` (about 6 minutes on 2 cores).
std::vector<CaseResult> b1_deformable_marble(const std::string& source_dir,
                                             const std::string& binary,
                                             const std::filesystem::path& figure);
std::vector<CaseResult> c1_marble_calibration(const std::string& source_dir,
                                              const std::string& binary,
                                              const std::filesystem::path& out);
// C2: `vorodec calibrate models/calibrate_granite.toml` into `out` (about 30 minutes), as C1.
std::vector<CaseResult> c2_granite_calibration(const std::string& source_dir,
                                               const std::string& binary,
                                               const std::filesystem::path& out);
// C3: `vorodec calibrate models/calibrate_marble_nu.toml` (the marble with both of its nu; about
// 30 minutes), as C1.
std::vector<CaseResult> c3_marble_two_nu_calibration(const std::string& source_dir,
                                                     const std::string& binary,
                                                     const std::filesystem::path& out);

// Load paths of the marble study (minutes): the confinement series and its Mohr-Coulomb and
// Hoek-Brown fits (B1), variable-amplitude cyclic loading (B2), direct tension and Brazilian.
std::vector<CaseResult> b1_marble_triaxial(const std::string& source_dir,
                                           const std::string& binary);
std::vector<CaseResult> b2_marble_cyclic(const std::string& source_dir, const std::string& binary);
// B2's rows, but the half-rate ones, with the marble calibrated to both of its nu
// (models/ucs_marble_two_nu.toml).
std::vector<CaseResult> b2_marble_cyclic_two_nu(const std::string& source_dir,
                                                const std::string& binary);
std::vector<CaseResult> marble_tension(const std::string& source_dir, const std::string& binary);
// The hand set against C3's two-nu set over seeds 42-46: UCS, E, both nu, direct and Brazilian
// tensile strength, and the modulus in tension (30 runs, about 3 minutes on 2 cores).
std::vector<CaseResult> marble_sets_over_seeds(const std::string& source_dir,
                                               const std::string& binary);

// Grain-based specimens: mineral area fractions of a side x side granite specimen (in-process,
// one row per mineral); Voronoi against Trigon sub-blocks on the granite model's grains (shear
// share of cracks, informational); the granite statics of [Li2018] (model runs).
std::vector<CaseResult> g1_mineral_fractions(double side, double grain_size);
std::vector<CaseResult> g2_voronoi_vs_trigon(const std::string& source_dir,
                                             const std::string& binary);
std::vector<CaseResult> b5_granite(const std::string& source_dir, const std::string& binary);

// Stiff and extreme cases: each must finish or stop with a clear message (exit code 3), never
// produce NaN, crash or hang.
struct StabilityOutcome {
  std::string name;
  std::string change;  // what the case changes in tests/models/e2e_small.toml
  int exit_code = -1;
  std::string status;   // summary.json status
  bool finite = false;  // every history value finite
  long steps = 0;
  double time_step = 0;  // s, summary.json time_step_s
  double seconds = 0;
  bool acceptable() const {
    return (exit_code == 0 || exit_code == 3) && finite && !status.empty();
  }
};
std::vector<StabilityOutcome> stability_cases(const std::string& source_dir,
                                              const std::string& binary);

// Zero damping, elastic bonds (strengths never reached): a bonded assembly of 30 Voronoi blocks
// with random initial velocities runs `steps` steps. Returns max |E - E0| / E0 of kinetic + strain
// energy, with the time-centred kinetic energy 1/2 m v(n-1/2).v(n+1/2) and with the plain one.
struct UndampedEnergy {
  // Relative to E0: the largest deviation of the time-centred (shadow) energy and of the plain
  // sum, and the shadow energy's drift, mean of the last tenth of the steps minus the first's
  // (its beating averages out there; the largest deviation holds both).
  double shadow = 0, plain = 0, drift = 0, dt = 0, seconds = 0;
  long steps = 0;
  std::size_t blocks = 0, contacts = 0;
};
// `safety` is solver.safety_factor; `shear_stiffness` (Pa/m) 0 leaves only normal springs.
UndampedEnergy undamped_energy(long steps, double safety = 0.8, double shear_stiffness = 7.3e12);
inline constexpr double undamped_energy_bound = 1e-3;  // on UndampedEnergy::shadow (issue 23)

// Convergence ladders: one quantity at a sequence of discretisations, coarse to fine.
struct LadderRung {
  double parameter = 0;  // the discretisation (time step, loading rate)
  double value = 0;
  double error = 0;  // relative to the ladder's reference
  double seconds = 0;
  bool is_default = false;  // the setting the code or the model uses by default
};
struct Ladder {
  std::string name, parameter, quantity;
  std::string reference;  // exact value, or the finest rung taken as converged
  double reference_value = 0;
  std::vector<LadderRung> rungs;
  // Observed order: least-squares slope of log(error) against log(parameter), rungs with error > 0.
  double order() const;
};
std::vector<Ladder> analytic_ladders();  // A3 period and A8 damping against the time step
// A10 displacement against the time step, from the consistent start (second order) and from a
// force stepped up from zero (first order).
std::vector<Ladder> a10_ladders();
// A11 with [Potyondy2007]'s frozen-rate estimate: the failure time's error against n_c (strength
// degradation, s = 0.7; the held integration is exact at any n_c).
Ladder a11_frozen_ladder();
// The default model (models/ucs_marble.toml), one thread: UCS and E against the platen speed and
// against the density-scaling time step, each relative to its finest run. Minutes.
std::vector<Ladder> model_ladders(const std::string& source_dir, const std::string& binary);
// tests/models/deformable_small.toml, elastic (strengths out of reach), one thread: the apparent
// Young's modulus against the zone size, relative to the finest zoning. About a minute.
Ladder deformable_ladder(const std::string& source_dir, const std::string& binary);
// deformable_joint against the zone size, at rounding lengths 0.2 and 1 mm (about a minute).
std::vector<Ladder> deformable_joint_ladders();

// Quasi-static speed-ups against a converged reference (issue 7): the default model at fixed
// platen speeds and with adaptive platen speeds (stage key adaptive_velocity), one thread each.
struct SpeedRun {
  std::string setting;                // what the run changes in models/ucs_marble.toml
  bool is_reference = false;          // the platen-speed ladder's finest run (1.25e-3 m/s)
  bool is_default = false;            // the model file as it is (5e-3 m/s)
  double ucs = 0, youngs = 0;         // Pa
  double ucs_error = 0, e_error = 0;  // relative to the reference run
  double seconds = 0;                 // wall time of the whole run (build included)
  long steps = 0;
};
// About 8 minutes on one core: the reference alone takes 3.
std::vector<SpeedRun> quasi_static_speed_runs(const std::string& source_dir,
                                              const std::string& binary);

// B4, the hard-sandstone creep study (model runs, about 15 minutes on 2 cores): its rows and the
// end-of-stage strains against the creep step.
struct CreepVerification {
  std::vector<CaseResult> rows;
  Ladder ladder;
};
CreepVerification b4_sandstone(const std::string& source_dir, const std::string& binary);

struct NamedCase {
  std::string id;
  std::function<CaseResult()> run;
};
std::vector<NamedCase> analytic_cases();

// B5 under impact: models/shpb_granite.toml at striker speeds 5-50 m/s, the static strength from
// models/ucs_granite_undamped.toml, and the dynamic strength at 10 m/s against the time step and
// against the sub-block size. Minutes.
struct ShpbRun {
  double speed = 0, seconds = 0;
  int exit_code = -1;
  std::string status;
  double strength = 0, rate = 0, eta_loading = 0, eta_peak = 0, strain_at_peak = 0;
  double ring_up = 0, eta_ring_up = 0;  // s, -: the end of the ring-up, largest |eta| after it
  double strain_end = 0;                // the last three-wave strain
  bool class_two = false;
  std::array<double, 4> crack_share{};  // of crack length, in measure::kCrackClassNames' order
  // The same impact with bars built from blocks: three-wave and face-force peaks, rate, time.
  double block_strength = 0, block_faces = 0, block_rate = 0, block_seconds = 0;
};
struct ShpbRise {
  double rise, strength, rate, eta_loading, eta_ring_up, eta_peak, equilibrium_time, seconds;
};
struct ShpbVerification {
  double static_strength = 0;  // Pa
  std::vector<ShpbRun> runs;
  std::vector<ShpbRise> rises;  // 10 m/s, the pulse's rise time varied
  Ladder ladder, block_ladder;
};
ShpbVerification b5_granite_shpb(const std::string& source_dir, const std::string& binary,
                                 const std::filesystem::path& work);

}  // namespace vorodec::verification
