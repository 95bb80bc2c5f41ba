#pragma once
// The convergence-ladder section of REPORT.md, its CSV (ladders.csv) and plot (ladders.png).
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
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

}  // namespace vorodec::verification
