// Grain-based specimens: mineral area fractions against the request (in-process), Voronoi
// against Trigon sub-blocks on the same grains, and the granite statics (whole-model runs).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "cases.hpp"
#include "model_runs.hpp"
#include "vorodec/geometry/grains.hpp"

namespace vorodec::verification {

namespace {

// The share of cracks that failed in shear at the row of peak stress and at the end of the run.
struct ShearShare {
  double at_peak = NAN, at_end = NAN;
};

ShearShare shear_share(const std::filesystem::path& history) {
  const Table h = read_table(history);
  ShearShare s;
  if (h.rows.empty()) return s;
  std::size_t peak = 0;
  for (std::size_t r = 0; r < h.rows.size(); ++r)
    if (h.number(r, "axial_stress") > h.number(peak, "axial_stress")) peak = r;
  const auto share = [&](std::size_t r) {
    const double t = h.number(r, "cracks_tensile"), sh = h.number(r, "cracks_shear");
    return t + sh > 0 ? sh / (t + sh) : NAN;
  };
  s.at_peak = share(peak);
  s.at_end = share(h.rows.size() - 1);
  return s;
}

}  // namespace

std::vector<CaseResult> g1_mineral_fractions(double side, double grain_size) {
  const auto t0 = std::chrono::steady_clock::now();
  geometry::TessellationSettings s;
  s.outline = {geometry::OutlineKind::rectangle, side, side, 0.0, 0};
  s.seed = 42;
  s.lloyd_iterations = 2;
  s.min_edge_length = 1e-4;
  geometry::GrainSettings g;
  g.grain_size = grain_size;
  g.sub_block_size = grain_size * 2 / 3;
  g.fractions = {0.517, 0.263, 0.195, 0.025};  // granite (B5): feldspar, quartz, biotite, other
  const geometry::Tessellation t = geometry::tessellate_grains(s, g);
  std::vector<double> grain_area(t.grain_mineral.size(), 0.0);
  for (std::size_t b = 0; b < t.blocks.size(); ++b) {
    const auto& blk = t.blocks[b];
    double twice = 0;
    for (std::size_t i = 0; i < blk.size(); ++i)
      twice += cross(t.vertices[blk[i]], t.vertices[blk[(i + 1) % blk.size()]]);
    grain_area[static_cast<std::size_t>(t.block_grain[b])] += twice / 2;
  }
  const double total = std::accumulate(grain_area.begin(), grain_area.end(), 0.0);
  const double largest = *std::max_element(grain_area.begin(), grain_area.end()) / total;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const char* names[] = {"feldspar", "quartz", "biotite", "other"};
  std::vector<CaseResult> r;
  for (std::size_t m = 0; m < g.fractions.size(); ++m) {
    const double achieved = t.mineral_area[m] / total;
    r.push_back({"G1", fmt::format("{} area fraction, {} grains", names[m], t.grain_mineral.size()),
                 "requested fraction; tolerance: the largest grain's share of the area",
                 g.fractions[m], achieved, std::abs(achieved - g.fractions[m]), largest,
                 fmt::format("{:g} x {:g} mm, grain {:g} mm, seed 42", side * 1e3, side * 1e3,
                             grain_size * 1e3),
                 seconds});
  }
  return r;
}

std::vector<CaseResult> g2_voronoi_vs_trigon(const std::string& source_dir,
                                             const std::string& binary) {
  const std::filesystem::path model = std::filesystem::path(source_dir) / "models/ucs_granite.toml";
  const auto base = std::filesystem::temp_directory_path() / "vorodec_verification";
  std::vector<CaseResult> r;
  for (const char* kind : {"voronoi", "trigon"}) {
    const auto out = base / fmt::format("g2_{}", kind);
    const ModelRun run =
        run_model(binary, model, out, fmt::format("--set specimen.sub_blocks={}", kind));
    const ShearShare s = shear_share(out / "history.csv");
    const std::string settings =
        fmt::format("models/ucs_granite.toml, sub_blocks = {}, {:g} blocks", kind,
                    json_number(run.summary, "blocks"));
    const std::string ref = "informational: users report triangles favour shear, Voronoi tension";
    CaseResult peak{"G2",       fmt::format("{}: shear share of cracks at peak stress", kind),
                    ref,        0,
                    s.at_peak,  0,
                    0,          settings,
                    run.seconds};
    peak.informational = true;
    CaseResult end = peak;
    end.name = fmt::format("{}: shear share of cracks at the end (50 % post-peak)", kind);
    end.measured = s.at_end;
    CaseResult ucs = peak;
    ucs.name = fmt::format("{}: UCS (Pa)", kind);
    ucs.measured = json_number(run.summary, "peak_stress_Pa");
    r.insert(r.end(), {peak, end, ucs});
  }
  return r;
}

std::vector<CaseResult> b5_granite(const std::string& source_dir, const std::string& binary) {
  const auto dir = std::filesystem::path(source_dir) / "models";
  const auto base = std::filesystem::temp_directory_path() / "vorodec_verification";
  const ModelRun u = run_model(binary, dir / "ucs_granite.toml", base / "b5_ucs");
  const ModelRun t = run_model(binary, dir / "tension_granite.toml", base / "b5_tension");
  const std::string paper = "granite static tests [Li2018]";
  std::vector<CaseResult> r;
  const auto add = [&](std::string name, double expected, double measured, const ModelRun& run,
                       std::string settings) {
    CaseResult c{"B5",       std::move(name),
                 paper,      expected,
                 measured,   std::abs(measured - expected) / expected,
                 0.10,       std::move(settings),
                 run.seconds};
    if (std::isnan(measured)) c.error = 1.0;
    r.push_back(c);
  };
  const std::string ucs = "models/ucs_granite.toml (grain-based, Voronoi sub-blocks)";
  add("UCS (Pa)", 129.6e6, json_number(u.summary, "peak_stress_Pa"), u, ucs);
  add("Young's modulus (Pa)", 42.3e9, json_number(u.summary, "youngs_modulus_Pa"), u, ucs);
  add("Poisson's ratio", 0.21, json_number(u.summary, "poisson_ratio"), u, ucs);
  r.push_back(energy_balance("B5", u, ucs));
  r.push_back(half_rate_ucs("B5", binary, dir / "ucs_granite.toml", u, base / "b5_ucs_half"));
  add("direct tensile strength (Pa)", 11.5e6, json_number(t.summary, "tensile_strength_Pa"), t,
      "models/tension_granite.toml (bonded platens)");
  return r;
}

}  // namespace vorodec::verification
