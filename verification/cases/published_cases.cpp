#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cases.hpp"
#include "model_runs.hpp"

namespace vorodec::verification {

std::vector<CaseResult> b1_marble_ucs(const std::string& source_dir, const std::string& binary) {
  const std::filesystem::path model = std::filesystem::path(source_dir) / "models/ucs_marble.toml";
  const auto out = std::filesystem::temp_directory_path() / "vorodec_verification/b1";
  const ModelRun s = run_model(binary, model, out);
  const std::string paper = "marble, UDEC Voronoi [Yu2023], Table 1";
  const std::string settings = "models/ucs_marble.toml: 1302 blocks, 5e-3 m/s, time_step 5e-7 s";
  std::vector<CaseResult> r;
  const auto add = [&](std::string name, double expected, double measured, double tol) {
    CaseResult c{"B1",     std::move(name), paper,
                 expected, measured,        std::abs(measured - expected) / expected,
                 tol,      settings,        s.seconds};
    if (std::isnan(measured)) c.error = 1.0;
    r.push_back(c);
  };
  add("UCS (Pa)", 47.89e6, json_number(s.summary, "peak_stress_Pa"), 0.05);
  r.push_back(energy_balance("B1", s, settings));
  add("Young's modulus at 50 % of peak (Pa)", 29.22e9, json_number(s.summary, "youngs_modulus_Pa"),
      0.05);
  add("Poisson's ratio", 0.225, json_number(s.summary, "poisson_ratio"), 0.05);

  r.push_back(half_rate_ucs("B1", binary, model, s, out.parent_path() / "b1_half"));
  return r;
}

}  // namespace vorodec::verification
