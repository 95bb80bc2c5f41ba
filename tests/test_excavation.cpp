// Excavation: the blocks inside the opening leave the model with every contact they had, bonds
// included, and the stage reports what the opening did.
#include <gtest/gtest.h>

#include <cmath>

#include "run_support.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"

using namespace vorodec;

namespace {
const std::string kSmall = std::string(VORODEC_SOURCE_DIR) + "/tests/models/tunnel_small.toml";
}

TEST(Excavation, RemovedBlocksLoseEveryContactAndStayPut) {
  const io::ModelConfig cfg = run::read_model_file(kSmall);
  const auto tess = run::make_specimen(cfg);
  run::PreparedModel p = run::prepare_model(cfg, tess);
  auto& bl = p.model->blocks;
  std::vector<std::uint32_t> inside;
  for (std::uint32_t b = 0; b < bl.size(); ++b)
    if (bl.group[b] == model::Group::specimen && std::hypot(bl.x[b] - 1.0, bl.y[b] - 1.0) < 0.4)
      inside.push_back(b);
  ASSERT_GT(inside.size(), 10u);
  std::size_t bonded_before = 0;
  for (const auto& c : p.model->contacts)
    for (const auto b : inside)
      bonded_before +=
          c.bonded && (c.a == static_cast<std::int32_t>(b) || c.b == static_cast<std::int32_t>(b));
  ASSERT_GT(bonded_before, 0u);
  p.solver->remove_blocks(inside);
  for (const auto& c : p.model->contacts)
    for (const auto b : inside) {
      EXPECT_NE(c.a, static_cast<std::int32_t>(b));
      EXPECT_NE(c.b, static_cast<std::int32_t>(b));
    }
  const double x = bl.x[inside[0]], y = bl.y[inside[0]];
  for (int k = 0; k < 50; ++k) p.solver->step();  // under gravity
  EXPECT_EQ(bl.x[inside[0]], x);
  EXPECT_EQ(bl.y[inside[0]], y);
  EXPECT_EQ(bl.group[inside[0]], model::Group::excavated);
}

TEST(Excavation, StageReportsTheRemovedBlocksAndTheOpeningsConvergence) {
  const std::filesystem::path out = vorodec::testing::out_dir("excavation_report");
  ASSERT_EQ(vorodec::testing::run_vorodec("run " + kSmall + " --out " + out.string()), 0);
  const std::string summary = vorodec::testing::slurp(out / "summary.json");
  // Every block well inside the circle goes and none well outside it (the in-situ loading moves
  // the centroids by about a millimetre before the excavation).
  const io::ModelConfig cfg = run::read_model_file(kSmall);
  run::PreparedModel p = run::prepare_model(cfg, run::make_specimen(cfg));
  const auto& bl = p.model->blocks;
  int well_inside = 0, near = 0;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    const double r = std::hypot(bl.x[b] - 1.0, bl.y[b] - 1.0);
    well_inside += bl.group[b] == model::Group::specimen && r < 0.4 - 0.005;
    near += bl.group[b] == model::Group::specimen && r < 0.4 + 0.005;
  }
  const auto at_removed = summary.find("\"removed_blocks\": ");
  ASSERT_NE(at_removed, std::string::npos) << summary;
  const int removed = std::stoi(summary.substr(at_removed + 18));
  EXPECT_GE(removed, well_inside);
  EXPECT_LE(removed, near);
  // The rock closes in on the opening.
  const auto at = summary.find("\"convergence_m\": ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_GT(std::stod(summary.substr(at + 17)), 0.0);
  EXPECT_NE(vorodec::testing::slurp(out / "history.csv").find("opening_convergence"),
            std::string::npos);
}
