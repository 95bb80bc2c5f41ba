// In-situ stress: the initial contacts carry the field's traction, so that the rock mass starts in
// equilibrium under it (docs/theory.md §6.7).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "run_support.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"

using namespace vorodec;

namespace {
const std::string kModel = std::string(VORODEC_SOURCE_DIR) + "/tests/models/in_situ_small.toml";

struct Settled {
  double moved;  // m, the largest block displacement
  double ratio;  // unbalanced-force ratio
};

// After `steps` steps with the platens held and the field's traction on the sides, from contacts
// preloaded with the field or (preload false) unloaded ones.
Settled settle(const std::vector<io::Override>& overrides, bool preload, int steps) {
  io::ModelConfig cfg = run::read_model_file(kModel, overrides);
  const loading::InSituStress given = *cfg.in_situ;
  if (!preload) cfg.in_situ.reset();
  run::PreparedModel p = run::prepare_model(cfg, run::make_specimen(cfg));
  const loading::SpecimenBoundary boundary(*p.model);
  const loading::InSituStress field = loading::resolved(given, *p.model);
  for (int k = 0; k < steps; ++k) {
    boundary.apply_stress(*p.model, field);
    p.solver->step();
  }
  const auto& bl = p.model->blocks;
  double moved = 0;
  for (std::size_t b = 0; b < bl.size(); ++b)
    moved = std::max(moved, std::hypot(bl.x[b] - bl.x0[b], bl.y[b] - bl.y0[b]));
  return {moved, p.solver->unbalanced_force_ratio()};
}
}  // namespace

TEST(InSitu, PreloadedContactsHoldAnAnisotropicFieldWithItsWeight) {
  // 5 / 10 MPa growing with depth by the rock's weight. Unloaded, the joints close by about
  // 1e-4 m each under the boundary stress; preloaded, the blocks move by a few per cent of that
  // (what is left: contact arms at the rounded corners, not at the shared edges' midpoints;
  // measured: 3.5e-6 m against 7.2e-4 m unloaded).
  const Settled loaded = settle({}, true, 300), unloaded = settle({}, false, 300);
  EXPECT_LT(loaded.moved, 0.05 * unloaded.moved);
  EXPECT_LT(loaded.moved, 1e-5);
  EXPECT_LT(loaded.ratio, 1e-3);
  EXPECT_GT(unloaded.ratio, 1e-2);
}

TEST(InSitu, PreloadedZonesAndContactsHoldTheFieldInZonedBlocks) {
  // The zones start with the field at their centroids, the contacts with its traction; unloaded,
  // the zones and joints close under the boundary stress (measured: 1.9e-6 m against 6.5e-4 m).
  const std::vector<io::Override> zoned{{"blocks.deformable", "true", "test"},
                                        {"blocks.zone_size", "0.05", "test"},
                                        {"blocks.E", "30e9", "test"},
                                        {"blocks.nu", "0.25", "test"}};
  const Settled loaded = settle(zoned, true, 300), unloaded = settle(zoned, false, 300);
  EXPECT_LT(loaded.moved, 0.05 * unloaded.moved);
  EXPECT_LT(loaded.ratio, 1e-3);
  EXPECT_GT(unloaded.ratio, 1e-2);
}

TEST(InSitu, PreloadedContactsHoldAShearStress) {
  const std::vector<io::Override> shear{{"in_situ.stress", "[5e6, 10e6, 2e6]", "test"}};
  const Settled loaded = settle(shear, true, 300), unloaded = settle(shear, false, 300);
  EXPECT_LT(loaded.moved, 0.05 * unloaded.moved);
  EXPECT_LT(loaded.ratio, 1e-3);
}

namespace {
struct SupportedRun {
  double convergence;     // m, the opening's mean convergence
  double lateral_strain;  // largest |lateral strain| of the run
};

SupportedRun run_with_sides(const std::string& sides) {
  const std::filesystem::path out = vorodec::testing::out_dir("in_situ_sides_" + sides);
  EXPECT_EQ(vorodec::testing::run_vorodec("run " + kModel + " --out " + out.string() +
                                          " --set loading.sides='\"" + sides + "\"'"),
            0);
  const auto rows = vorodec::testing::read_csv(out / "history.csv");
  double lateral = 0;
  for (const auto& r : rows) lateral = std::max(lateral, std::abs(r[4]));
  const std::string summary = vorodec::testing::slurp(out / "summary.json");
  const auto at = summary.find("\"convergence_m\":");
  EXPECT_NE(at, std::string::npos);
  return {std::stod(summary.substr(at + 16)), lateral};
}
}  // namespace

TEST(InSitu, RollerAndFixedSidesHoldTheSideBlocksWhereTheStressLetsThemMove) {
  const SupportedRun stress = run_with_sides("stress"), roller = run_with_sides("roller"),
                     fixed = run_with_sides("fixed");
  EXPECT_GT(stress.lateral_strain, 1e-5);  // the sides move out as the opening is dug
  EXPECT_EQ(roller.lateral_strain, 0.0);   // the side blocks (the gauges) never move across
  EXPECT_EQ(fixed.lateral_strain, 0.0);
  EXPECT_GT(roller.convergence, 0.0);
  // Fixed sides also hold the rock beside them up: the opening converges less.
  EXPECT_LT(fixed.convergence, 0.8 * roller.convergence);
}
