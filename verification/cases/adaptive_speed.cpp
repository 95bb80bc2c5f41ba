#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cases.hpp"
#include "model_runs.hpp"

namespace vorodec::verification {

std::vector<SpeedRun> quasi_static_speed_runs(const std::string& source_dir,
                                              const std::string& binary) {
  namespace fs = std::filesystem;
  const fs::path model = fs::path(source_dir) / "models/ucs_marble.toml";
  const fs::path dir = fs::temp_directory_path() / "vorodec_verification/speeds";
  struct Plan {
    std::string name, setting, set;
  };
  const auto adaptive = [](double ratio) {
    return Plan{
        fmt::format("adaptive_{:g}", ratio),
        fmt::format("adaptive, target ratio {:g}, 1.25e-3 ... 2e-2 m/s (start 5e-3 m/s)", ratio),
        fmt::format("--set 'stage[0].adaptive_velocity={{target_ratio={:g},"
                    "min_velocity=1.25e-3,max_velocity=2e-2}}'",
                    ratio)};
  };
  const auto fixed = [](double v) {
    return Plan{fmt::format("fixed_{:g}", v), fmt::format("fixed {:g} m/s", v),
                fmt::format("--set stage[0].platen_velocity={:g}", v)};
  };
  const auto implicit = [](int increments) {
    return Plan{fmt::format("implicit_{}", increments),
                fmt::format("implicit elastic start, {} increment{}, then fixed 5e-3 m/s",
                            increments, increments > 1 ? "s" : ""),
                fmt::format("--set stage[0].implicit_start=true "
                            "--set stage[0].implicit_start_increments={}",
                            increments)};
  };
  Plan implicit_adaptive = adaptive(5e-4);
  implicit_adaptive.name = "implicit_adaptive";
  implicit_adaptive.setting =
      "implicit elastic start (10 increments), then " + implicit_adaptive.setting;
  implicit_adaptive.set += " --set stage[0].implicit_start=true";
  // The reference first: every error is relative to it.
  const std::vector<Plan> plans{fixed(1.25e-3), fixed(1e-2),      fixed(5e-3),    fixed(2.5e-3),
                                adaptive(1e-3), adaptive(5e-4),   adaptive(2e-4), implicit(1),
                                implicit(10),   implicit_adaptive};
  std::vector<SpeedRun> runs;
  for (const Plan& p : plans) {
    const fs::path out = dir / p.name;
    fs::create_directories(out);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string cmd =
        fmt::format("{} run {} --no-vtk --threads 1 {} --out {} > {}/log.txt 2>&1", binary,
                    model.string(), p.set, out.string(), out.string());
    SpeedRun r;
    r.setting = p.setting;
    r.is_reference = runs.empty();
    r.is_default = p.name == "fixed_0.005";
    r.ucs = r.youngs = std::nan("");
    if (std::system(cmd.c_str()) == 0) {
      std::ifstream in(out / "summary.json");
      const std::string text{std::istreambuf_iterator<char>(in), {}};
      r.ucs = json_number(text, "peak_stress_Pa");
      r.youngs = json_number(text, "youngs_modulus_Pa");
      r.steps = static_cast<long>(json_number(text, "steps"));
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const SpeedRun& ref = runs.empty() ? r : runs.front();
    r.ucs_error = (r.ucs - ref.ucs) / ref.ucs;
    r.e_error = (r.youngs - ref.youngs) / ref.youngs;
    runs.push_back(r);
  }
  return runs;
}

}  // namespace vorodec::verification
