// Jointed specimens: joint sets and fracture files cut the Voronoi blocks, and the contacts across
// a joint take its set's law.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/geometry/joints.hpp"

using namespace vorodec;
namespace fs = std::filesystem;

namespace {

geometry::TessellationSettings specimen() {
  geometry::TessellationSettings s;
  s.outline = {geometry::OutlineKind::rectangle, 0.05, 0.1, 0, 0};
  s.block_count = 400;
  s.seed = 7;
  return s;
}

// Distance of p from the trace's segment.
double distance(geometry::Point p, const geometry::JointTrace& t) {
  const geometry::Point d = t.b - t.a;
  const double u = std::clamp(dot(p - t.a, d) / dot(d, d), 0.0, 1.0);
  const geometry::Point q = t.a + u * d - p;
  return std::sqrt(dot(q, q));
}

}  // namespace

TEST(JointSets, NonPersistentTracesCutOnlyAlongTheirTraces) {
  const auto s = specimen();
  geometry::JointSetGeometry g;
  g.dip_deg = 20;
  g.spacing = 0.02;
  g.trace = 0.02;
  g.gap = 0.01;
  g.origin = {0.025, 0.05};
  const auto traces = geometry::joint_set_traces(g, s.outline, 0, s.seed);
  const auto cut = geometry::cut_by_joints(geometry::tessellate(s), traces, s);
  ASSERT_FALSE(cut.joint_edges.empty());
  // Every joint edge's blocks meet on a trace: each shared corner of the pair lies on one.
  for (const auto& j : cut.joint_edges) {
    std::set<std::uint32_t> a(cut.blocks[j.a].begin(), cut.blocks[j.a].end());
    int on_trace = 0;
    for (const auto v : cut.blocks[j.b]) {
      if (!a.count(v)) continue;
      double nearest = 1;
      for (const auto& t : traces) nearest = std::min(nearest, distance(cut.vertices[v], t));
      on_trace += nearest < 1e-9;
    }
    EXPECT_GE(on_trace, 2) << "blocks " << j.a << " and " << j.b;
  }
  // The joints are shorter than the traces inside the specimen (bridges stay intact rock).
  double joints = 0, inside = 0;
  for (const auto& j : cut.joint_edges) joints += j.length;
  for (const auto& t : traces) {
    for (int k = 0; k < 1000; ++k) {
      const geometry::Point p = t.a + ((k + 0.5) / 1000) * (t.b - t.a);
      if (p.x > 0 && p.x < 0.05 && p.y > 0 && p.y < 0.1)
        inside += std::sqrt(dot(t.b - t.a, t.b - t.a)) / 1000;
    }
  }
  EXPECT_GT(joints, 0.5 * inside);
  EXPECT_LE(joints, inside * 1.001);
}

TEST(JointSets, SameSeedGivesTheSameJointedSpecimen) {
  auto s = specimen();
  geometry::JointSetGeometry g;
  g.dip_deg = 70;
  g.spacing = 0.015;
  g.dip_spread = 5;
  g.spacing_spread = 0.003;
  const auto a = geometry::cut_by_joints(geometry::tessellate(s),
                                         geometry::joint_set_traces(g, s.outline, 0, s.seed), s);
  const auto b = geometry::cut_by_joints(geometry::tessellate(s),
                                         geometry::joint_set_traces(g, s.outline, 0, s.seed), s);
  ASSERT_EQ(a.blocks, b.blocks);
  ASSERT_EQ(a.joint_edges.size(), b.joint_edges.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    EXPECT_EQ(a.vertices[i].x, b.vertices[i].x);
    EXPECT_EQ(a.vertices[i].y, b.vertices[i].y);
  }
}

TEST(JointSets, ContactsAcrossAFractureTakeItsSetsLaw) {
  const fs::path dir = fs::temp_directory_path() / "vorodec_joint_sets";
  fs::create_directories(dir);
  std::ofstream(dir / "dfn.csv") << "x1,y1,x2,y2,set\n0,0.03,0.05,0.05,faults\n"
                                    "0.01,0,0.03,0.1,faults\n";
  std::ofstream(dir / "m.toml") << R"(seed = 3
[specimen]
width = 0.05
height = 0.1
block_count = 300
[blocks]
density = 2600
[joints]
jkn = 2e13
jks = 8e12
tension = 10e6
cohesion = 20e6
friction = 30
[[joint_set]]
name = "file"
file = "dfn.csv"
jkn = 2e13
jks = 8e12
friction = 30
[[joint_set]]
name = "faults"
law = "barton_bandis"
jkn = 2e10
max_closure = 5e-4
jks = 2e9
jrc = 8
jcs = 80e6
residual_friction = 28
[[stage]]
platen_velocity = 0.05
end_axial_strain = 0.001
)";
  const io::ModelConfig cfg = run::read_model_file(dir / "m.toml");
  ASSERT_EQ(cfg.joint_sets.size(), 2u);
  EXPECT_TRUE(cfg.joint_sets[0].fractures.empty());  // every row names the second set
  EXPECT_EQ(cfg.joint_sets[1].fractures.size(), 2u);
  const auto tess = run::make_specimen(cfg);
  std::set<std::pair<std::uint32_t, std::uint32_t>> faults;
  double length = 0;
  for (const auto& j : tess.joint_edges) {
    EXPECT_EQ(j.set, 1);
    faults.insert({j.a, j.b});
    length += j.length;
  }
  // Both fractures cross the specimen: 0.0539 m and 0.102 m.
  EXPECT_NEAR(length, std::hypot(0.05, 0.02) + std::hypot(0.02, 0.1), 1e-4);
  run::PreparedModel p = run::prepare_model(cfg, tess);
  const auto& laws = p.solver->laws();
  std::size_t across = 0;
  for (const auto& c : p.model->contacts) {
    if (p.model->blocks.group[static_cast<std::size_t>(c.a)] != model::Group::specimen ||
        p.model->blocks.group[static_cast<std::size_t>(c.b)] != model::Group::specimen)
      continue;
    const auto a = static_cast<std::uint32_t>(c.a), b = static_cast<std::uint32_t>(c.b);
    const std::pair<std::uint32_t, std::uint32_t> key{std::min(a, b), std::max(a, b)};
    const bool joint = faults.count(key) > 0;
    across += joint;
    EXPECT_EQ(laws[c.law]->name(), joint ? "barton_bandis" : "mohr_coulomb");
  }
  EXPECT_GT(across, 2 * faults.size() - 1);  // two point contacts per joint edge at least
}
