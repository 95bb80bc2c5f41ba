#pragma once
// The convergence-ladder section of REPORT.md, its CSV (ladders.csv) and plot (ladders.png).
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "cases/cases.hpp"

namespace vorodec::verification {

inline void write_ladders(std::ostream& out, const std::vector<Ladder>& analytic,
                          const std::vector<Ladder>& model, const std::filesystem::path& dir,
                          const std::string& source_dir) {
  std::vector<Ladder> all = analytic;
  all.insert(all.end(), model.begin(), model.end());
  out << "\n## Convergence ladders\n\nEach ladder runs one quantity at a sequence of "
         "discretisations, coarse to fine. Error is relative to the exact value (analytic "
         "cases) or to the ladder's finest run, taken as converged (the default model: its own "
         "error is 0 by construction and it is left out of the fit). The observed order is the "
         "least-squares slope of log(error) against log(parameter). `*` marks the default "
         "setting (solver safety factor 0.8; the model file's 5e-3 m/s and 5e-7 s). Plot: "
         "`ladders.png` (data `ladders.csv`, `verification/plot_ladders.py`).\n";
  if (model.empty())
    out << "\nThe whole-model ladders were not run this time (`verification/run.sh build "
           "--ladders`).\n";
  std::ofstream csv(dir / "ladders.csv");
  csv << "ladder,parameter_name,quantity,reference,parameter,value,error,seconds,default,order\n";
  for (const Ladder& l : all) {
    out << fmt::format("\n### {}\n\nReference: {} = {:.6g}. Observed order: {:.2f}.\n\n", l.name,
                       l.reference, l.reference_value, l.order())
        << fmt::format("| {} | {} | error | wall time |\n|---|---|---|---|\n", l.parameter,
                       l.quantity);
    for (const LadderRung& r : l.rungs) {
      out << fmt::format("| {:.4g}{} | {:.6g} | {:.3g} | {:.2f} s |\n", r.parameter,
                         r.is_default ? " *" : "", r.value, r.error, r.seconds);
      csv << fmt::format("\"{}\",\"{}\",\"{}\",\"{}\",{:.9g},{:.9g},{:.6g},{:.3f},{},{:.4g}\n",
                         l.name, l.parameter, l.quantity, l.reference, r.parameter, r.value,
                         r.error, r.seconds, r.is_default ? 1 : 0, l.order());
    }
  }
  csv.close();
  const std::filesystem::path script =
      std::filesystem::path(source_dir) / "verification/plot_ladders.py";
  const std::string cmd =
      fmt::format("/usr/bin/python3 {} {} {}", script.string(), (dir / "ladders.csv").string(),
                  (dir / "ladders.png").string());
  if (std::system(cmd.c_str()) == 0) out << "\n![convergence ladders](ladders.png)\n";
}

inline std::string order_text(const Ladder& l);

// <stem>.csv and, by verification/plot_cost_accuracy.py, <stem>.png: the ladder's error against
// wall time, its observed order only where the errors fall monotonically (else NaN: "no trend").
// True if the plot was drawn.
inline bool cost_accuracy_plot(const Ladder& l, const std::filesystem::path& dir,
                               const std::string& source_dir, const std::string& stem) {
  std::ofstream csv(dir / (stem + ".csv"));
  csv << "parameter,value,error,seconds,default,order\n";
  const bool monotone = order_text(l).find("no trend") == std::string::npos;
  const double order = monotone ? l.order() : std::numeric_limits<double>::quiet_NaN();
  for (const LadderRung& r : l.rungs)
    csv << fmt::format("{:.9g},{:.9g},{:.6g},{:.3f},{},{:.4g}\n", r.parameter, r.value, r.error,
                       r.seconds, r.is_default ? 1 : 0, order);
  csv.close();
  const std::string cmd = fmt::format(
      "/usr/bin/python3 {} {} {} '{}'",
      (std::filesystem::path(source_dir) / "verification/plot_cost_accuracy.py").string(),
      (dir / (stem + ".csv")).string(), (dir / (stem + ".png")).string(), l.name);
  return std::system(cmd.c_str()) == 0;
}

// The observed order where the errors fall monotonically as the setting is refined, else "no
// trend" (an order fitted through points that rise and fall says nothing).
inline std::string order_text(const Ladder& l) {
  for (std::size_t i = 1; i < l.rungs.size(); ++i)
    if (!(l.rungs[i].error < l.rungs[i - 1].error))
      return "no trend (the errors do not fall monotonically)";
  return fmt::format("{:.2f}", l.order());
}

// A whole-model ladder as error against wall time (a cost-accuracy table and plot,
// creep_ladder.csv / creep_ladder.png).
inline void write_creep_ladder(std::ostream& out, const Ladder& l, const std::filesystem::path& dir,
                               const std::string& source_dir) {
  out << fmt::format(
      "\n## {}\n\nReference: {} = {:.6g}. Observed order (in the creep step): "
      "{:.2f}. `*` marks the default.\n\n| {} | {} | error | wall time |\n"
      "|---|---|---|---|\n",
      l.name, l.reference, l.reference_value, l.order(), l.parameter, l.quantity);
  for (const LadderRung& r : l.rungs)
    out << fmt::format("| {:.4g}{} | {:.6g} | {:.3g} | {:.1f} s |\n", r.parameter,
                       r.is_default ? " *" : "", r.value, r.error, r.seconds);
  if (cost_accuracy_plot(l, dir, source_dir, "creep_ladder"))
    out << "\n![error against run time](creep_ladder.png)\n";
}

// The error-vs-run-time table of the quasi-static speed-ups (issue 7): fixed and adaptive platen
// speeds and the implicit elastic start on the default model against the platen-speed ladder's
// finest run.
inline void write_speed_runs(std::ostream& out, const std::vector<SpeedRun>& runs) {
  out << "\n## Quasi-static runs: error against run time\n\n`models/ucs_marble.toml` (1302 "
         "blocks, density-scaling time step 5e-7 s, one thread) to 50 % post-peak at fixed and "
         "adaptive platen speeds (`adaptive_velocity`: default interval 500 steps, largest change "
         "x1.25 per interval), and with the implicit elastic start (`implicit_start`: CHOLMOD "
         "solves of the contact stiffness carry the specimen to 0.9 of the platen displacement "
         "at which the first contact would leave its elastic regime, in 1 or 10 increments). "
         "Errors are signed, relative to the reference (`ref`, the finest "
         "rung of the platen-speed ladder); `*` marks the model file as it is. Wall time is the "
         "whole run, specimen build included.\n\n"
      << "| run | steps | wall time | UCS (Pa) | UCS error | E (Pa) | E error |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const SpeedRun& r : runs)
    out << fmt::format("| {}{} | {} | {:.1f} s | {:.6g} | {:+.3g} | {:.6g} | {:+.3g} |\n",
                       r.setting,
                       r.is_reference ? " (ref)"
                       : r.is_default ? " *"
                                      : "",
                       r.steps, r.seconds, r.ucs, r.ucs_error, r.youngs, r.e_error);
}

}  // namespace vorodec::verification
