#include "calibration_report.hpp"

#include <fmt/format.h>

#include <set>

#include "vorodec/io/atomic_file.hpp"

namespace vorodec::workflows {

namespace fs = std::filesystem;

namespace {

std::string number(double v) {
  return fmt::format("{:.6g}", v);
}

// A value as the target's unit reads best: MPa, GPa, degrees, plain.
std::string pretty(const CalibrationTarget& t, double v) {
  const std::string& q = t.quantity;
  if (q == "youngs_modulus_Pa" || q == "linear_youngs_modulus_Pa")
    return fmt::format("{:.2f} GPa", v / 1e9);
  if (q.size() > 3 && q.substr(q.size() - 3) == "_Pa") return fmt::format("{:.2f} MPa", v / 1e6);
  if (q == "friction_angle_deg") return fmt::format("{:.2f} deg", v);
  return fmt::format("{:.4g}", v);
}

std::string tolerance_text(const CalibrationTarget& t) {
  return t.absolute ? pretty(t, t.tolerance) : fmt::format("{:g} %", 100 * t.tolerance);
}

std::string error_text(const CalibrationTarget& t, double mean) {
  return t.absolute ? fmt::format("{:+.3g}", mean - t.value)
                    : fmt::format("{:+.2f} %", 100 * (mean - t.value) / t.value);
}

double tie_value(const Tie& tie, const std::vector<double>& v) {
  double x = tie.constant;
  for (const std::size_t p : tie.times) x *= v[p];
  for (const std::size_t p : tie.divided_by) x /= v[p];
  return x;
}

}  // namespace

void write_history(const fs::path& out, const CalibrationPlan& plan,
                   const std::vector<Evaluation>& history) {
  std::string s = "evaluation,phase,runs,elapsed_s,longest_run_s,failed_runs,objective,worst,best";
  for (const CalibrationParameter& p : plan.parameters) s.append(",").append(p.name);
  for (const CalibrationTarget& t : plan.targets)
    s += fmt::format(",{0}_mean,{0}_sd,{0}_error_over_tolerance", t.name);
  s += '\n';
  for (const Evaluation& e : history) {
    s += fmt::format("{},{},{},{:.1f},{:.1f},{},{},{},{}", e.index, e.phase, e.runs,
                     e.elapsed_seconds, e.wall_seconds, e.failed_runs, number(e.objective),
                     number(e.worst), e.best);
    for (const double v : e.values) s.append(",").append(number(v));
    for (std::size_t t = 0; t < e.mean.size(); ++t)
      s += fmt::format(",{},{},{}", number(e.mean[t]), number(e.scatter[t]),
                       number(e.scaled_error[t]));
    s += '\n';
  }
  io::write_file_atomically(out / "history.csv", s);
  std::string t = "target,quantity,value,tolerance,absolute,weight\n";
  for (const CalibrationTarget& g : plan.targets)
    t += fmt::format("{},{},{},{},{},{}\n", g.name, g.quantity, number(g.value),
                     number(g.tolerance), g.absolute ? 1 : 0, number(g.weight));
  io::write_file_atomically(out / "targets.csv", t);
}

void write_sensitivity(const fs::path& out, const CalibrationPlan& plan,
                       const std::vector<Evaluation>& history,
                       const std::vector<Sensitivity>& rounds) {
  std::string s =
      "round,base_evaluation,moved_evaluation,target,parameter,parameter_base,parameter_moved,"
      "target_base,target_moved,elasticity,d_error_over_tolerance_d_unit\n";
  const std::size_t n = plan.parameters.size();
  for (std::size_t r = 0; r < rounds.size(); ++r) {
    const Evaluation& base = history[rounds[r].base - 1];
    for (std::size_t j = 0; j < n; ++j) {
      const Evaluation& moved = history[rounds[r].evaluations[j] - 1];
      for (std::size_t i = 0; i < plan.targets.size(); ++i)
        s += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", r + 1, base.index, moved.index,
                         plan.targets[i].name, plan.parameters[j].name, number(base.values[j]),
                         number(moved.values[j]), number(base.mean[i]), number(moved.mean[i]),
                         number(rounds[r].elasticity[i * n + j]),
                         number(rounds[r].jacobian[i * n + j]));
    }
  }
  io::write_file_atomically(out / "sensitivity.csv", s);
}

void write_calibrated_models(const fs::path& out, const CalibrationPlan& plan,
                             const Evaluation& best) {
  std::set<fs::path> models;
  for (const CalibrationTest& t : plan.tests) models.insert(t.model);
  for (const fs::path& model : models) {
    std::string s = fmt::format(
        "# Calibrated by `vorodec calibrate {}` (evaluation {}): targets and scatter in "
        "report.md.\nbase = \"{}\"\n",
        plan.file.string(), best.index,
        fs::relative(fs::absolute(model), fs::absolute(out)).string());
    const auto line = [&s](const std::string& key, double v, const std::string& why) {
      // A key with an array index ("stage[0].x") has no TOML dotted form: pass it with --set.
      s += key.find('[') == std::string::npos ? fmt::format("{} = {}  # {}\n", key, v, why)
                                              : fmt::format("# --set {}={} ({})\n", key, v, why);
    };
    for (std::size_t i = 0; i < plan.parameters.size(); ++i)
      if (plan.parameters[i].model_key) line(plan.parameters[i].name, best.values[i], "calibrated");
    for (const Tie& tie : plan.ties) line(tie.key, tie_value(tie, best.values), "tied");
    for (std::size_t i = 0; i < plan.parameters.size(); ++i)
      if (!plan.parameters[i].model_key)
        s += fmt::format("# {} = {} (a free parameter of the ties)\n", plan.parameters[i].name,
                         best.values[i]);
    io::write_file_atomically(out / fmt::format("calibrated_{}.toml", model.stem().string()), s);
  }
}

void write_report(const fs::path& out, const CalibrationPlan& plan,
                  const std::vector<Evaluation>& history, const std::vector<Sensitivity>& rounds,
                  const Evaluation& best, bool converged, double elapsed_seconds) {
  std::size_t runs = history.empty() ? 0 : history.back().runs;
  std::string s =
      fmt::format("# Calibration: {}\n\n", plan.title.empty() ? plan.file.string() : plan.title);
  s += fmt::format(
      "`vorodec calibrate {}`: **{}**. Best: evaluation {} of {}; {} runs ({} tests x {} seeds "
      "per evaluation); {:.0f} s of wall time (budget {} runs, {:.0f} s).\n\n",
      plan.file.string(),
      converged ? "every target within its tolerance" : "budget spent before every target was met",
      best.index, history.size(), runs, plan.tests.size(), plan.seeds.size(), elapsed_seconds,
      plan.max_runs, plan.max_wall_seconds);
  s += "## Targets\n\nMean over the seeds, and their standard deviation (the seed-to-seed "
       "scatter).\n\n| target | quantity | wanted | achieved | scatter (sd) | error | tolerance "
       "| met |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t t = 0; t < plan.targets.size(); ++t) {
    const CalibrationTarget& g = plan.targets[t];
    s += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |\n", g.name, g.quantity,
                     pretty(g, g.value), pretty(g, best.mean[t]), pretty(g, best.scatter[t]),
                     error_text(g, best.mean[t]), tolerance_text(g),
                     std::abs(best.scaled_error[t]) <= 1 ? "yes" : "**no**");
  }
  s += "\n## Parameters\n\n| parameter | start | calibrated | bounds | scale |\n"
       "|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < plan.parameters.size(); ++i) {
    const CalibrationParameter& p = plan.parameters[i];
    s += fmt::format("| {} | {:.4g} | {:.4g} | [{:g}, {:g}] | {} |\n", p.name, p.start,
                     best.values[i], p.min, p.max, p.log_scale ? "log" : "linear");
  }
  for (const Tie& tie : plan.ties)
    s += fmt::format("| {} (tied) | | {:.4g} | | |\n", tie.key, tie_value(tie, best.values));
  if (!rounds.empty()) {
    const Sensitivity& r = rounds.back();
    const std::size_t n = plan.parameters.size();
    s += fmt::format(
        "\n## Sensitivity (micro-macro relations)\n\nd ln(target) / d ln(parameter) around "
        "evaluation {}{}, one parameter moved by {:g} % at a time (sensitivity.csv has every "
        "round).\n\n| target |",
        r.base, r.base == best.index ? " (the calibrated set)" : "", 100 * plan.step);
    for (const CalibrationParameter& p : plan.parameters) s.append(" ").append(p.name).append(" |");
    s += "\n|---|";
    for (std::size_t j = 0; j < n; ++j) s += "---|";
    s += '\n';
    for (std::size_t i = 0; i < plan.targets.size(); ++i) {
      s.append("| ").append(plan.targets[i].name).append(" |");
      for (std::size_t j = 0; j < n; ++j) s += fmt::format(" {:+.2f} |", r.elasticity[i * n + j]);
      s += '\n';
    }
  }
  s += "\n## History\n\n| evaluation | phase | runs | elapsed (s) | objective | worst "
       "(tolerances) |\n|---|---|---|---|---|---|\n";
  for (const Evaluation& e : history)
    s += fmt::format("| {} | {} | {} | {:.0f} | {:.4g} | {:.2f} |\n", e.index, e.phase, e.runs,
                     e.elapsed_seconds, e.objective, e.worst);
  s += fmt::format(
      "\nMethod: every evaluation runs each test with each seed; the same seeds every time give "
      "the same specimens and Weibull draws (common random numbers), so parameter changes are "
      "not lost in seed noise. Objective: the weighted mean of (error / tolerance)^2. Search: "
      "the start, a dimensional first guess, a one-at-a-time sensitivity round and its "
      "least-squares step, then NLopt's BOBYQA in [0, 1] coordinates (log or linear per "
      "parameter), stopped when every target is within its tolerance.\n\nPlots: "
      "`/usr/bin/python3 postproc/plot_calibration.py {}` (objective history, targets against "
      "runs, the sensitivity heat map, the micro-macro relations).\n",
      out.string());
  io::write_file_atomically(out / "report.md", s);
}

}  // namespace vorodec::workflows
