#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "cases.hpp"
#include "model_runs.hpp"

namespace vorodec::verification {

namespace fs = std::filesystem;

namespace {

const std::string paper = "marble cyclic loading [Yu2023]";
constexpr double reference_ucs = 47.89e6;  // Pa, the paper's simulated UCS

struct Line {
  double intercept = 0, slope = 0, r2 = 0;
};

// Least-squares line y = intercept + slope x, with its coefficient of determination.
Line fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
    syy += y[i] * y[i];
  }
  Line l;
  const double den = n * sxx - sx * sx;
  if (den == 0) return l;
  l.slope = (n * sxy - sx * sy) / den;
  l.intercept = (sy - l.slope * sx) / n;
  const double ss_tot = syy - sy * sy / n;
  double ss_res = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double e = y[i] - (l.intercept + l.slope * x[i]);
    ss_res += e * e;
  }
  l.r2 = ss_tot > 0 ? 1.0 - ss_res / ss_tot : 0.0;
  return l;
}

}  // namespace

std::vector<CaseResult> b1_marble_triaxial(const std::string& source_dir,
                                           const std::string& binary) {
  const fs::path batch = fs::path(source_dir) / "models/batch_confinement.toml";
  const fs::path out = fs::temp_directory_path() / "vorodec_verification/b1_triaxial";
  fs::remove_all(out);
  const auto t0 = std::chrono::steady_clock::now();
  const std::string cmd = fmt::format("{} batch {} --no-vtk --out {} > /dev/null 2>&1", binary,
                                      batch.string(), out.string());
  const int status = std::system(cmd.c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Table t = read_table(out / "results.csv");
  std::vector<double> s3, s1;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    s3.push_back(t.number(i, "loading.confining_stress"));
    s1.push_back(t.number(i, "peak_stress_Pa"));
  }
  const std::string settings = fmt::format(
      "models/batch_confinement.toml: {} runs at 0-20 MPa (exit status {}), peaks of sigma1",
      t.rows.size(), WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  // Mohr-Coulomb: sigma1 = sigma_c + k sigma3, k = (1 + sin phi) / (1 - sin phi).
  const Line mc = fit_line(s3, s1);
  const double sin_phi = (mc.slope - 1) / (mc.slope + 1);
  const double phi = std::asin(sin_phi) * 180 / std::numbers::pi;
  const double c = mc.intercept * (1 - sin_phi) / (2 * std::sqrt(1 - sin_phi * sin_phi));
  std::vector<CaseResult> r;
  const std::string fit = paper + ": peaks at 0-20 MPa fit by c 15.3 MPa, phi 25 deg";
  r.push_back(relative("B1", "Mohr-Coulomb cohesion of the peak envelope (Pa)", fit, 15.3e6, c,
                       0.10, settings, seconds));
  CaseResult f{"B1",   "Mohr-Coulomb friction angle of the peak envelope (deg; error in deg)",
               fit,    25.0,
               phi,    std::abs(phi - 25.0),
               3.0,    settings,
               seconds};
  if (!std::isfinite(f.error)) f.error = 99;
  r.push_back(f);
  // Hoek-Brown (s = 1): (sigma1 - sigma3)^2 = sigma_c^2 + m_i sigma_c sigma3.
  std::vector<double> y(s1.size());
  for (std::size_t i = 0; i < s1.size(); ++i) y[i] = (s1[i] - s3[i]) * (s1[i] - s3[i]);
  const Line hb = fit_line(s3, y);
  const double sigma_c = std::sqrt(std::max(hb.intercept, 0.0));
  CaseResult hb_c{"B1",
                  "Hoek-Brown sigma_c of the peaks (Pa)",
                  "derived; no published value",
                  0,
                  sigma_c,
                  0,
                  0,
                  settings,
                  seconds,
                  true};
  CaseResult hb_m{"B1",
                  fmt::format("Hoek-Brown m_i of the peaks (fit R^2 {:.3f})", hb.r2),
                  "derived; no published value",
                  0,
                  sigma_c > 0 ? hb.slope / sigma_c : 0,
                  0,
                  0,
                  settings,
                  seconds,
                  true};
  r.push_back(hb_c);
  r.push_back(hb_m);
  for (std::size_t i = 0; i < s1.size(); ++i) {
    const double k = (1 + std::sin(25.0 * std::numbers::pi / 180)) /
                     (1 - std::sin(25.0 * std::numbers::pi / 180));
    const double expected = reference_ucs + k * s3[i];
    r.push_back(relative("B1", fmt::format("peak stress at {:g} MPa confinement (Pa)", s3[i] / 1e6),
                         "the paper's envelope: 47.9 MPa + 2.46 sigma3", expected, s1[i], 0.10,
                         settings, seconds));
  }
  return r;
}

namespace {

// Length-weighted fraction of the cracks formed before `time` whose line lies at 70-110 deg.
double steep_crack_fraction(const fs::path& cracks_csv, double time) {
  const Table c = read_table(cracks_csv);
  double steep = 0, all = 0;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    if (c.number(i, "time") >= time) continue;
    const double len = c.number(i, "length"), ang = c.number(i, "orientation_deg");
    all += len;
    if (ang >= 70 && ang <= 110) steep += len;
  }
  return all > 0 ? steep / all : 0.0;
}

// Worst deviation of the stress from each unloading's ramp (after the first 10 % of its span),
// relative to the span.
double worst_ramp_deviation(const Table& h, double rate, double lower) {
  double worst = 0, t0 = 0, s0 = 0;
  bool in = false;
  for (std::size_t i = 0; i < h.rows.size(); ++i) {
    const std::string& stage = h.rows[i][static_cast<std::size_t>(h.column("stage"))];
    const bool unload = stage.find("_unload") != std::string::npos;
    if (!unload) {
      in = false;
      continue;
    }
    const double t = h.number(i, "time"), s = h.number(i, "axial_stress");
    if (!in) {
      in = true;
      t0 = t;
      s0 = s;
      continue;
    }
    const double target = std::max(s0 - rate * (t - t0), lower);
    if (s0 - target > 0.1 * (s0 - lower))
      worst = std::max(worst, std::abs(s - target) / (s0 - lower));
  }
  return worst;
}

// Damage density gained in each cycle: at its unloading's end minus at its loading's start.
std::vector<double> damage_per_cycle(const Table& h, int cycles) {
  std::vector<double> d;
  const int col = h.column("stage");
  for (int k = 1; k <= cycles; ++k) {
    double begin = std::nan(""), end = std::nan("");
    for (std::size_t i = 0; i < h.rows.size(); ++i) {
      const std::string& st = h.rows[i][static_cast<std::size_t>(col)];
      if (st == fmt::format("cycle{}_load:start", k)) begin = h.number(i, "damage_density");
      if (st == fmt::format("cycle{}_unload:end", k)) end = h.number(i, "damage_density");
    }
    d.push_back(end - begin);
  }
  return d;
}

// B2's rows of one cyclic run (every row's name starts with `label`): energy balance, the first
// loading, the trends over the cycles, the cracks' orientation, damage per cycle, the ramp.
std::vector<CaseResult> b2_cycle_rows(const ModelRun& run, const std::string& label,
                                      const std::string& settings, double rate) {
  const Table cyc = read_table(run.out / "cycles.csv");
  const Table h = read_table(run.out / "history.csv");
  const std::string b2 = paper + ", B2";
  std::vector<CaseResult> r;
  r.push_back(energy_balance("B2", run, settings));
  r.back().name = label + r.back().name;
  r.push_back(relative("B2", label + "secant modulus of the first loading (Pa)",
                       b2 + ": starts at about 30 GPa", 30e9, cyc.number(0, "secant_modulus_Pa"),
                       0.10, settings, run.seconds));
  r.push_back(relative("B2", label + "generalized Poisson's ratio of the first loading",
                       b2 + ": about 0.18 at the first loading", 0.18,
                       cyc.number(0, "poisson_ratio"), 0.10, settings, run.seconds));
  // Trends across the cycles that completed (a stalled cycle is the last).
  int rises = 0, residual_falls = 0;
  for (std::size_t k = 1; k < cyc.rows.size(); ++k) {
    rises += cyc.number(k, "secant_modulus_Pa") > 1.01 * cyc.number(k - 1, "secant_modulus_Pa");
    residual_falls += cyc.number(k, "residual_strain") < cyc.number(k - 1, "residual_strain");
  }
  r.push_back({"B2", label + "cycles whose secant modulus rises by > 1 % over the previous one",
               b2 + ": the simulated secant modulus falls with the cycles", 0, double(rises),
               double(rises), 0, settings, run.seconds});
  r.push_back({"B2", label + "cycles whose residual strain falls below the previous one",
               b2 + ": residual strain grows with the upper stress ratio", 0,
               double(residual_falls), double(residual_falls), 0, settings, run.seconds});
  // Cracks below 80 % of the peak lie mostly at 70-110 degrees.
  double t80 = std::nan("");
  for (std::size_t i = 0; i < h.rows.size() && std::isnan(t80); ++i)
    if (h.number(i, "axial_stress") >= 0.8 * reference_ucs) t80 = h.number(i, "time");
  const double steep = steep_crack_fraction(run.out / "cracks.csv", t80);
  r.push_back({"B2",
               label + "share of crack length at 70-110 deg before 80 % of peak (lower bound 0.5)",
               b2 + ": failed contacts lie mostly at 70-110 deg below 80 % of peak", 0.5, steep,
               std::max(0.0, 0.5 - steep), 0, settings, run.seconds});
  // Damage density per cycle against the upper stress ratio: D = R a^s.
  std::vector<double> la, ld;
  const auto gained = damage_per_cycle(h, static_cast<int>(cyc.rows.size()));
  for (std::size_t k = 0; k < gained.size(); ++k)
    if (gained[k] > 0) {
      la.push_back(std::log(cyc.number(k, "upper_reached_Pa") / reference_ucs));
      ld.push_back(std::log(gained[k]));
    }
  const Line fit = fit_line(la, ld);
  r.push_back({"B2",
               label + fmt::format("damage density per cycle D = R a^s: R^2 of the fit over {} "
                                   "cycles (R = {:.3g}, s = {:.3g}; lower bound 0.9)",
                                   la.size(), std::exp(fit.intercept), fit.slope),
               b2 + ": exponential growth with the upper stress ratio (form, not constants)", 0.9,
               fit.r2, std::max(0.0, 0.9 - fit.r2), 0, settings, run.seconds});
  r.push_back({"B2", label + "worst deviation of the unloading stress from its ramp (/ span)",
               "stress-rate control: sigma = sigma_upper - rate t", 0,
               worst_ramp_deviation(h, rate, 0.0), worst_ramp_deviation(h, rate, 0.0), 0.02,
               settings, run.seconds});
  return r;
}

}  // namespace

std::vector<CaseResult> b2_marble_cyclic(const std::string& source_dir, const std::string& binary) {
  const fs::path model = fs::path(source_dir) / "models/cyclic_marble.toml";
  const fs::path out = fs::temp_directory_path() / "vorodec_verification/b2";
  constexpr double rate = 1.5e9;  // Pa/s, the model's unloading rate
  ModelRun run, half;
  {
    // The model and the same at half the unloading rate (the rate's reference), side by side.
    std::thread other([&] {
      half = run_model(binary, model, out.parent_path() / "b2_half",
                       "--threads 1 --set stage[0].unloading_rate=7.5e8");
    });
    run = run_model(binary, model, out, "--threads 1");
    other.join();
  }
  const Table cyc = read_table(out / "cycles.csv");
  const std::string settings = fmt::format(
      "models/cyclic_marble.toml: 5 cycles to +20 % of 47.9 MPa, unloading 1.5e9 Pa/s; exit {}",
      run.exit_code);
  std::vector<CaseResult> r = b2_cycle_rows(run, "", settings, rate);
  // The unloading rate must not decide the answer: half the rate as the reference.
  const Table cyc_half = read_table(out.parent_path() / "b2_half/cycles.csv");
  const std::size_t last = std::min(cyc.rows.size(), cyc_half.rows.size());
  if (last > 0) {
    const std::string half_settings =
        fmt::format("half unloading rate 7.5e8 Pa/s, cycle {} (exit {})", last, half.exit_code);
    r.push_back(relative("B2", fmt::format("secant modulus of cycle {} (Pa)", last),
                         "converged-rate reference: the same model at half the unloading rate",
                         cyc_half.number(last - 1, "secant_modulus_Pa"),
                         cyc.number(last - 1, "secant_modulus_Pa"), 0.02, half_settings,
                         half.seconds));
    r.push_back(relative("B2", "dissipated work summed over the cycles (J/m^3)",
                         "converged-rate reference: the same model at half the unloading rate",
                         cyc_half.number(last - 1, "dissipated_total_J_m3"),
                         cyc.number(last - 1, "dissipated_total_J_m3"), 0.10, half_settings,
                         half.seconds));
  }
  return r;
}

std::vector<CaseResult> b2_marble_cyclic_two_nu(const std::string& source_dir,
                                                const std::string& binary) {
  const fs::path models = fs::path(source_dir) / "models";
  const fs::path out = fs::temp_directory_path() / "vorodec_verification/b2_two_nu";
  const ModelRun run = run_model(binary, models / "cyclic_marble.toml", out,
                                 set_arguments(models / "ucs_marble_two_nu.toml"));
  const std::string settings = fmt::format(
      "models/cyclic_marble.toml with the set of models/ucs_marble_two_nu.toml (C3); {} cycles; "
      "exit {}",
      read_table(out / "cycles.csv").rows.size(), run.exit_code);
  return b2_cycle_rows(run, "two-nu set: ", settings, 1.5e9);
}

std::vector<CaseResult> marble_tension(const std::string& source_dir, const std::string& binary) {
  const fs::path models = fs::path(source_dir) / "models";
  const fs::path out = fs::temp_directory_path() / "vorodec_verification";
  ModelRun pull, disc;
  {
    std::thread other([&] {
      disc = run_model(binary, models / "brazilian_marble.toml", out / "brazilian", "--threads 1");
    });
    pull = run_model(binary, models / "tension_marble.toml", out / "tension", "--threads 1");
    other.join();
  }
  const double direct = json_number(pull.summary, "tensile_strength_Pa");
  const double brazilian = json_number(disc.summary, "tensile_strength_Pa");
  std::vector<CaseResult> r;
  r.push_back({"BT", "direct tensile strength (Pa)", "derived; the paper gives none", 0, direct, 0,
               0, "models/tension_marble.toml", pull.seconds, true});
  r.push_back(relative(
      "BT",
      "Brazilian tensile strength 2F/(pi D t) (sin 2a - a)/a, flats 2a = 20 deg, against the "
      "direct tensile strength (Pa)",
      "elastic disc theory: the Brazilian formula is the tensile stress at the disc centre "
      "(Hondros 1959 for a load spread over 2a), so for a brittle material it equals the direct "
      "tensile strength (ISRM 1978)",
      direct, brazilian, 0.25,
      "models/brazilian_marble.toml: 50 mm flattened disc (flats 20 deg), 511 blocks",
      disc.seconds));
  r.push_back(relative("BT", "Young's modulus in tension against in compression (Pa)",
                       "same contacts, linear before cracking: equal moduli (B1 target 29.2 GPa)",
                       29.22e9, json_number(pull.summary, "youngs_modulus_Pa"), 0.05,
                       "models/tension_marble.toml", pull.seconds));
  r.push_back(energy_balance("BT", pull, "models/tension_marble.toml (direct tension)"));
  r.push_back(
      energy_balance("BT", disc, "models/brazilian_marble.toml (flattened Brazilian disc)"));
  return r;
}

}  // namespace vorodec::verification
