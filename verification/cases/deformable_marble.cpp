// B1D: the deformable-block marble against the paper's laboratory values and against the rigid
// marble of B1 (issue 26): what deformability changes.
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cases.hpp"
#include "model_runs.hpp"

namespace vorodec::verification {

namespace {
// m, the length of the tensile or shear cracks of a run: counts would not compare, since a
// zoned block's joint is cut into one contact per boundary gridpoint.
double crack_length(const ModelRun& run, const std::string& type) {
  const Table t = read_table(run.out / "cracks.csv");
  const int kind = t.column("type");
  if (kind < 0) return std::nan("");
  double sum = 0;
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    if (t.rows[i][static_cast<std::size_t>(kind)] == type) sum += t.number(i, "length");
  return sum;
}
}  // namespace

std::vector<CaseResult> b1_deformable_marble(const std::string& source_dir,
                                             const std::string& binary,
                                             const std::filesystem::path& figure) {
  const std::filesystem::path models = std::filesystem::path(source_dir) / "models";
  const auto out = std::filesystem::temp_directory_path() / "vorodec_verification";
  const ModelRun rigid = run_model(binary, models / "ucs_marble.toml", out / "b1d_rigid");
  const ModelRun zoned =
      run_model(binary, models / "ucs_deformable_marble.toml", out / "b1d_deformable");
  const std::string paper = "marble, UDEC Voronoi [Yu2023], Table 1";
  const std::string settings =
      "models/ucs_deformable_marble.toml: 1302 blocks, 1 mm zones, blocks E 70 GPa";
  std::vector<CaseResult> r;
  const auto add = [&](std::string name, std::string reference, double expected, double measured,
                       double tol, double seconds) {
    CaseResult c{"B1D",    std::move(name), std::move(reference),
                 expected, measured,        std::abs(measured - expected) / std::abs(expected),
                 tol,      settings,        seconds};
    if (std::isnan(c.error)) c.error = 1.0;
    r.push_back(c);
  };
  add("UCS (Pa)", paper, 47.89e6, json_number(zoned.summary, "peak_stress_Pa"), 0.05,
      zoned.seconds);
  add("Young's modulus at 50 % of peak (Pa)", paper, 29.22e9,
      json_number(zoned.summary, "youngs_modulus_Pa"), 0.05, zoned.seconds);
  add("Poisson's ratio", paper, 0.225, json_number(zoned.summary, "poisson_ratio"), 0.05,
      zoned.seconds);
  r.push_back(energy_balance("B1D", zoned, settings));
  // Crack initiation (the start of the crack-count rise) over the peak, against the rigid model's.
  const auto ci = [](const ModelRun& run) {
    return json_number(run.summary, "crack_initiation_stress_Pa") /
           json_number(run.summary, "peak_stress_Pa");
  };
  add("crack initiation stress / peak", "the rigid marble (models/ucs_marble.toml, B1's run)",
      ci(rigid), ci(zoned), 0.25, rigid.seconds + zoned.seconds);
  // What deformability changes, reported against the rigid model (no reference to judge by).
  for (const auto& [name, ratio] :
       {std::pair{"UCS, deformable / rigid", json_number(zoned.summary, "peak_stress_Pa") /
                                                 json_number(rigid.summary, "peak_stress_Pa")},
        std::pair{"E, deformable / rigid", json_number(zoned.summary, "youngs_modulus_Pa") /
                                               json_number(rigid.summary, "youngs_modulus_Pa")},
        std::pair{"nu, deformable / rigid", json_number(zoned.summary, "poisson_ratio") /
                                                json_number(rigid.summary, "poisson_ratio")},
        std::pair{"tensile crack length at the end, deformable / rigid",
                  crack_length(zoned, "tensile") / crack_length(rigid, "tensile")},
        std::pair{"shear crack length at the end, deformable / rigid",
                  crack_length(zoned, "shear") / crack_length(rigid, "shear")},
        std::pair{"wall time, deformable / rigid", zoned.seconds / rigid.seconds}}) {
    CaseResult c{"B1D", name, "the rigid marble (B1's model)", 1.0, ratio, 0, 0, settings, 0, true};
    r.push_back(c);
  }
  const std::string plot = fmt::format(
      "/usr/bin/python3 {}/postproc/compare_runs.py {} {} --labels rigid deformable -o {}",
      source_dir, rigid.out.string(), zoned.out.string(), figure.string());
  if (std::system(plot.c_str()) != 0)
    std::fprintf(stderr, "B1D: the figure failed: %s\n", plot.c_str());
  return r;
}

}  // namespace vorodec::verification
