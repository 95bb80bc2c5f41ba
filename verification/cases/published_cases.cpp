#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cases.hpp"

namespace vorodec::verification {

namespace {

double json_number(const std::string& text, const std::string& key) {
  const std::string tag = "\"" + key + "\": ";
  const auto pos = text.find(tag);
  return pos == std::string::npos ? std::nan("")
                                  : std::strtod(text.c_str() + pos + tag.size(), nullptr);
}

struct Summary {
  std::string text;
  double seconds;
};

Summary run_model(const std::string& binary, const std::filesystem::path& model,
                  const std::filesystem::path& out) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string cmd = fmt::format("{} run {} --no-vtk --out {} > {}/log.txt 2>&1", binary,
                                      model.string(), out.string(), out.string());
  std::filesystem::create_directories(out);
  if (std::system(cmd.c_str()) == -1) return {"", 0};
  std::ifstream in(out / "summary.json");
  return {{std::istreambuf_iterator<char>(in), {}},
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

}  // namespace

std::vector<CaseResult> b1_marble_ucs(const std::string& source_dir, const std::string& binary) {
  const std::filesystem::path model = std::filesystem::path(source_dir) / "models/ucs_marble.toml";
  const auto out = std::filesystem::temp_directory_path() / "vorodec_verification/b1";
  const Summary s = run_model(binary, model, out);
  const std::string paper =
      "marble, UDEC Voronoi (variable-amplitude cyclic loading paper, Rock Mech Rock Eng), Table 1";
  const std::string settings = "models/ucs_marble.toml: 1302 blocks, 5e-3 m/s, time_step 5e-7 s";
  std::vector<CaseResult> r;
  const auto add = [&](std::string name, double expected, double measured, double tol) {
    CaseResult c{"B1",     std::move(name), paper,
                 expected, measured,        std::abs(measured - expected) / expected,
                 tol,      settings,        s.seconds};
    if (std::isnan(measured)) c.error = 1.0;
    r.push_back(c);
  };
  add("UCS (Pa)", 47.89e6, json_number(s.text, "peak_stress_Pa"), 0.05);
  {
    // Energy balance at the end of the run (PHYSICS section 10): boundary work against strain +
    // kinetic + damping + friction + breakage, from the last history row.
    std::ifstream hist(out / "history.csv");
    std::string line, header, last;
    std::getline(hist, header);
    while (std::getline(hist, line)) last = line;
    const auto split = [](const std::string& text) {
      std::vector<std::string> cells;
      for (std::size_t p = 0; p <= text.size();) {
        const auto q = std::min(text.find(',', p), text.size());
        cells.push_back(text.substr(p, q - p));
        p = q + 1;
      }
      return cells;
    };
    const std::vector<std::string> names = split(header), cells = split(last);
    // The last row's value in the named column (columns are found by name, not position).
    const auto column = [&](const char* name) {
      const auto it = std::find(names.begin(), names.end(), name);
      const auto i = static_cast<std::size_t>(it - names.begin());
      return it != names.end() && i < cells.size() ? std::strtod(cells[i].c_str(), nullptr)
                                                   : std::nan("");
    };
    CaseResult e{"B1",
                 "energy balance at the end of the run (imbalance / boundary work)",
                 "boundary work = contact strain + kinetic + damping + friction + breakage",
                 0,
                 0,
                 0,
                 0.01,
                 settings,
                 s.seconds};
    e.error = 1.0;
    const double work = column("boundary_work");
    const double stored = column("strain_energy") + column("kinetic_energy") +
                          column("damping_energy") + column("friction_energy") +
                          column("breakage_energy");
    if (std::isfinite(work) && std::isfinite(stored) && work != 0) {
      e.measured = (work - stored) / work;
      e.error = std::abs(e.measured);
    }
    r.push_back(e);
  }
  add("Young's modulus at 50 % of peak (Pa)", 29.22e9, json_number(s.text, "youngs_modulus_Pa"),
      0.05);
  add("Poisson's ratio", 0.225, json_number(s.text, "poisson_ratio"), 0.05);

  // The loading rate must not decide the UCS: the same model at half the platen speed.
  std::ifstream in(model);
  std::string text{std::istreambuf_iterator<char>(in), {}};
  const std::string from = "platen_velocity = 5e-3 ";
  if (const auto pos = text.find(from); pos != std::string::npos)
    text.replace(pos, from.size(), "platen_velocity = 2.5e-3 ");
  const auto half = out.parent_path() / "b1_half_rate.toml";
  std::ofstream(half) << text;
  const Summary h = run_model(binary, half, out.parent_path() / "b1_half");
  CaseResult c{"B1",
               "UCS at 5e-3 m/s against UCS at 2.5e-3 m/s",
               "converged-rate reference: the same model at half the loading rate",
               json_number(h.text, "peak_stress_Pa"),
               json_number(s.text, "peak_stress_Pa"),
               0,
               0.02,
               "half rate: 2.5e-3 m/s",
               h.seconds};
  c.error = std::abs(c.measured - c.expected) / c.expected;
  if (std::isnan(c.error)) c.error = 1.0;
  r.push_back(c);
  return r;
}

}  // namespace vorodec::verification
