// Excavation: the blocks inside the opening leave the model with every contact they had, bonds
// included, and the stage reports what the opening did.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "run_support.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/measure/joint_displacement.hpp"
#include "vorodec/model/contact_geometry.hpp"

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

TEST(Excavation, JointSlipAndOpeningAreTheBlocksRelativeDisplacementAcrossTheJoint) {
  const io::ModelConfig cfg = run::read_model_file(kSmall);
  run::PreparedModel p = run::prepare_model(cfg, run::make_specimen(cfg));
  auto& m = *p.model;
  auto& bl = m.blocks;
  const int first = p.solver->law_table().joint_set_law;
  ASSERT_GE(first, 0);
  const measure::BlockPlacement at = measure::placement_of(bl);
  // A rigid motion of the whole model (turn 0.01 rad about (1, 1), shift (3, -2) mm) moves no
  // joint.
  for (std::size_t b = 0; b < bl.size(); ++b) {
    const double c = std::cos(0.01), s = std::sin(0.01), x = bl.x[b] - 1, y = bl.y[b] - 1;
    bl.x[b] = 1 + c * x - s * y + 0.003;
    bl.y[b] = 1 + s * x + c * y - 0.002;
    bl.theta[b] += 0.01;
  }
  model::refresh_world(m);
  for (const double d : measure::joint_displacements(m, at, first, 1)) EXPECT_LT(d, 1e-12);
  // One block of a bedding contact shifted 0.1 mm along the joint: that contact slips 0.1 mm and
  // none of the set more; then 0.1 mm away from its neighbour across the joint: it opens 0.1 mm.
  const measure::BlockPlacement moved = measure::placement_of(bl);
  const auto joint = std::find_if(m.contacts.begin(), m.contacts.end(),
                                  [&](const model::Contact& c) { return c.law == first; });
  ASSERT_NE(joint, m.contacts.end());
  model::Contact k = *joint;
  const model::ContactFrame f = model::contact_frame(bl, k);
  const auto a = static_cast<std::size_t>(k.a);
  bl.x[a] += 1e-4 * -f.n.y;
  bl.y[a] += 1e-4 * f.n.x;
  model::refresh_world(m);
  const std::vector<double> slid = measure::joint_displacements(m, moved, first, 1);
  EXPECT_NEAR(slid[0], 1e-4, 1e-12);
  bl.x[a] = moved.x[a] + 1e-4 * f.n.x;
  bl.y[a] = moved.y[a] + 1e-4 * f.n.y;
  model::refresh_world(m);
  EXPECT_NEAR(measure::joint_displacements(m, moved, first, 1)[1], 1e-4, 1e-12);
}

TEST(Excavation, GradualReleaseHoldsTheOpeningBackWhileItLasts) {
  // tunnel_small releases the opening over 0.02 s; released at once, the lining has moved
  // further by then.
  const std::filesystem::path slow = vorodec::testing::out_dir("excavation_slow");
  const std::filesystem::path sudden = vorodec::testing::out_dir("excavation_sudden");
  ASSERT_EQ(vorodec::testing::run_vorodec("run " + kSmall + " --out " + slow.string()), 0);
  ASSERT_EQ(vorodec::testing::run_vorodec("run " + kSmall + " --out " + sudden.string() +
                                          " --set stage[1].relaxation_time=0"),
            0);
  const auto convergence_at = [](const std::filesystem::path& dir, double t) {
    std::istringstream header(vorodec::testing::slurp(dir / "history.csv"));
    std::string line;
    std::getline(header, line);
    std::size_t u = 0;
    std::istringstream names(line);
    for (std::string name; std::getline(names, name, ',') && name != "opening_convergence";) ++u;
    for (const auto& row : vorodec::testing::read_csv(dir / "history.csv"))
      if (row[1] >= t) return row.at(u);  // column 1: time (s)
    return std::nan("");
  };
  const double t = 0.02 + 0.01;  // the in-situ stage ends at 0.02 s; halfway through the release
  EXPECT_LT(convergence_at(slow, t), 0.8 * convergence_at(sudden, t));
  EXPECT_GT(convergence_at(slow, t), 0.0);
}

TEST(Excavation, ZonedBlocksAreDugOutWithTheirGridpointsHeld) {
  const std::string zoned = std::string(VORODEC_SOURCE_DIR) + "/tests/models/tunnel_zoned.toml";
  const io::ModelConfig cfg = run::read_model_file(zoned);
  run::PreparedModel p = run::prepare_model(cfg, run::make_specimen(cfg));
  const auto& bl = p.model->blocks;
  const auto& z = p.model->zoning;
  std::vector<std::uint32_t> inside;
  for (std::uint32_t b = 0; b < bl.size(); ++b)
    if (bl.group[b] == model::Group::specimen && std::hypot(bl.x[b] - 1.0, bl.y[b] - 1.0) < 0.4)
      inside.push_back(b);
  ASSERT_GT(inside.size(), 10u);
  ASSERT_TRUE(bl.deformable[inside[0]]);
  p.solver->remove_blocks(inside);
  std::size_t held = 0;
  for (std::size_t g = 0; g < z.gridpoints(); ++g) held += z.block[g] == inside[0];
  ASSERT_GT(held, 3u);
  for (const auto& c : p.model->contacts)
    EXPECT_TRUE(c.a != static_cast<std::int32_t>(inside[0]) &&
                c.b != static_cast<std::int32_t>(inside[0]));
  std::vector<double> x(z.x), y(z.y);
  for (int k = 0; k < 50; ++k) p.solver->step();  // under gravity
  for (std::size_t g = 0; g < z.gridpoints(); ++g)
    if (z.block[g] == inside[0]) {
      EXPECT_EQ(z.x[g], x[g]);
      EXPECT_EQ(z.y[g], y[g]);
    }
  // The whole stage: the opening converges, and the dug zones leave the VTK frames.
  const std::filesystem::path out = vorodec::testing::out_dir("excavation_zoned");
  ASSERT_EQ(vorodec::testing::run_vorodec("run " + zoned + " --out " + out.string()), 0);
  const std::string summary = vorodec::testing::slurp(out / "summary.json");
  const auto at = summary.find("\"convergence_m\":");
  ASSERT_NE(at, std::string::npos);
  EXPECT_GT(std::stod(summary.substr(at + 16)), 1e-5);
}
