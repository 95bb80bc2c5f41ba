#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "cases.hpp"
#include "model_runs.hpp"

namespace vorodec::verification {

double Ladder::order() const {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const LadderRung& r : rungs) {
    if (!(r.error > 0) || !std::isfinite(r.error)) continue;
    const double x = std::log(r.parameter), y = std::log(r.error);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return n < 2 ? std::nan("") : (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

namespace {

struct LadderRun {
  double ucs = std::nan(""), youngs = std::nan(""), seconds = 0;
};

}  // namespace

std::vector<Ladder> model_ladders(const std::string& source_dir, const std::string& binary) {
  namespace fs = std::filesystem;
  const fs::path model = fs::path(source_dir) / "models/ucs_marble.toml";
  const fs::path dir = fs::temp_directory_path() / "vorodec_verification/ladders";
  constexpr double v0 = 5e-3, dt0 = 5e-7;               // the model file's own settings
  std::map<std::pair<double, double>, LadderRun> runs;  // the default run is shared
  const auto run = [&](double velocity, double dt) {
    auto [it, fresh] = runs.try_emplace({velocity, dt});
    if (!fresh) return it->second;
    const fs::path out = dir / fmt::format("v{:g}_dt{:g}", velocity, dt);
    fs::create_directories(out);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string cmd = fmt::format(
        "{} run {} --no-vtk --threads 1 --set stage[0].platen_velocity={:g} "
        "--set solver.time_step={:g} --out {} > {}/log.txt 2>&1",
        binary, model.string(), velocity, dt, out.string(), out.string());
    if (std::system(cmd.c_str()) == 0) {
      std::ifstream in(out / "summary.json");
      const std::string text{std::istreambuf_iterator<char>(in), {}};
      it->second.ucs = json_number(text, "peak_stress_Pa");
      it->second.youngs = json_number(text, "youngs_modulus_Pa");
    }
    it->second.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return it->second;
  };
  std::vector<Ladder> out;
  const auto ladder = [&](const std::string& what, const std::string& parameter,
                          const std::vector<double>& values, bool velocity) {
    std::vector<LadderRun> r;
    for (double p : values) r.push_back(velocity ? run(p, dt0) : run(v0, p));
    const std::string finest =
        fmt::format("finest run ({} = {:g}), taken as converged", what, values.back());
    for (int q = 0; q < 2; ++q) {
      Ladder l{fmt::format("ucs_marble: {} against {}", q ? "E" : "UCS", what),
               parameter,
               q ? "Young's modulus (Pa)" : "UCS (Pa)",
               finest,
               q ? r.back().youngs : r.back().ucs,
               {}};
      for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = q ? r[i].youngs : r[i].ucs;
        l.rungs.push_back({values[i], v, std::abs(v - l.reference_value) / l.reference_value,
                           r[i].seconds, values[i] == (velocity ? v0 : dt0)});
      }
      out.push_back(l);
    }
  };
  ladder("platen speed", "platen speed (m/s), time step 5e-7 s", {1e-2, 5e-3, 2.5e-3, 1.25e-3},
         true);
  ladder("time step", "density-scaling time step (s), 5e-3 m/s", {2e-6, 1e-6, 5e-7, 2.5e-7}, false);
  return out;
}

Ladder deformable_ladder(const std::string& source_dir, const std::string& binary) {
  namespace fs = std::filesystem;
  const fs::path model = fs::path(source_dir) / "tests/models/deformable_small.toml";
  const fs::path dir = fs::temp_directory_path() / "vorodec_verification/deformable_ladder";
  const std::vector<double> sizes{8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4};
  Ladder l{"deformable_small (40 deformable Voronoi blocks): E against zone size",
           "zone size (m); density-scaling time step 1e-6 s x min(1, zone size / 2 mm)",
           "Young's modulus (Pa)",
           "finest run (zone size 2.5e-4 m), taken as converged",
           0,
           {}};
  std::vector<LadderRun> runs;
  for (double h : sizes) {
    // The scaled gridpoint masses grow with the number of gridpoints unless the step shrinks
    // with the zones: keep the scaled inertia per area fixed.
    const double dt = 1e-6 * std::min(1.0, h / 2e-3);
    const fs::path out = dir / fmt::format("h{:g}", h);
    fs::create_directories(out);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string cmd = fmt::format(
        "{} run {} --no-vtk --threads 1 --set blocks.zone_size={:g} --set solver.time_step={:g} "
        "--set joints.tension=1e10 --set joints.cohesion=1e10 "
        "--set stage[0].end_axial_strain=1e-3 --out {} > {}/log.txt 2>&1",
        binary, model.string(), h, dt, out.string(), out.string());
    LadderRun r;
    if (std::system(cmd.c_str()) == 0) {
      std::ifstream in(out / "summary.json");
      r.youngs = json_number({std::istreambuf_iterator<char>(in), {}}, "youngs_modulus_Pa");
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    runs.push_back(r);
  }
  l.reference_value = runs.back().youngs;
  for (std::size_t i = 0; i < sizes.size(); ++i)
    l.rungs.push_back({sizes[i], runs[i].youngs,
                       std::abs(runs[i].youngs - l.reference_value) / l.reference_value,
                       runs[i].seconds, sizes[i] == 2e-3});
  return l;
}

}  // namespace vorodec::verification
