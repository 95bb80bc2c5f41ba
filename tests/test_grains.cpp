// Grain-based specimens: minerals by area fraction, sub-blocks that match along grain boundaries,
// contacts that know whether they cross a grain boundary, grain files, crack classes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <utility>

#include "run_support.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/geometry/grains.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/io/json.hpp"
#include "vorodec/measure/grain_cracks.hpp"

namespace {

using namespace vorodec;
using vorodec::testing::json_number;
using vorodec::testing::read_csv;
using vorodec::testing::run_capture;
using vorodec::testing::slurp;
namespace fs = std::filesystem;

const fs::path kSmall = fs::path(VORODEC_SOURCE_DIR) / "tests/models/grains_small.toml";

double area(const geometry::Tessellation& t, const std::vector<std::uint32_t>& b) {
  double twice = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    twice += cross(t.vertices[b[i]], t.vertices[b[(i + 1) % b.size()]]);
  return twice / 2;
}

geometry::TessellationSettings square(double side, std::uint64_t seed) {
  geometry::TessellationSettings s;
  s.outline = {geometry::OutlineKind::rectangle, side, side, 0.0, 0};
  s.seed = seed;
  s.min_edge_length = 5e-5;
  return s;
}

TEST(Grains, MineralAreaFractionsMatchTheRequestWithinTheProvenBound) {
  geometry::GrainSettings g;
  g.grain_size = 1e-3;
  g.sub_block_size = 6e-4;
  g.fractions = {0.517, 0.263, 0.195, 0.025};
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const geometry::Tessellation t = geometry::tessellate_grains(square(0.02, seed), g);
    // The largest grain, from its sub-blocks.
    std::vector<double> grain_area(t.grain_mineral.size(), 0.0);
    for (std::size_t b = 0; b < t.blocks.size(); ++b)
      grain_area[static_cast<std::size_t>(t.block_grain[b])] += area(t, t.blocks[b]);
    const double total = std::accumulate(grain_area.begin(), grain_area.end(), 0.0);
    const double largest = *std::max_element(grain_area.begin(), grain_area.end());
    ASSERT_EQ(t.mineral_area.size(), g.fractions.size());
    for (std::size_t m = 0; m < g.fractions.size(); ++m) {
      const double achieved = t.mineral_area[m] / total;
      EXPECT_LE(std::abs(achieved - g.fractions[m]), 3 * largest / total)
          << "seed " << seed << " mineral " << m;
    }
    EXPECT_GT(t.grain_mineral.size(), 400u);  // ~509 grains of 1 mm in 20 x 20 mm
  }
}

TEST(Grains, GreedyAssignmentHitsFractionsOfEqualGrainsExactly) {
  const std::vector<double> areas(100, 1.0);
  const std::vector<double> fractions{0.5, 0.3, 0.2};
  const auto mineral = geometry::assign_minerals(areas, fractions, 9);
  std::vector<int> count(3, 0);
  for (const auto m : mineral) ++count[static_cast<std::size_t>(m)];
  EXPECT_EQ(count, (std::vector<int>{50, 30, 20}));
}

// Every block edge is shared by exactly two blocks unless it lies on the outline: sub-blocks of
// neighbouring grains share every vertex along grain boundaries (no T-junctions left).
void expect_matching_edges(geometry::SubBlocks kind) {
  geometry::GrainSettings g;
  g.grain_size = 2e-3;
  g.sub_block_size = 1e-3;
  g.sub_blocks = kind;
  g.fractions = {0.5, 0.5};
  const double side = 0.01;
  const geometry::Tessellation t = geometry::tessellate_grains(square(side, 4), g);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& b : t.blocks) {
    EXPECT_GT(area(t, b), 0.0);
    if (kind == geometry::SubBlocks::trigon) {
      EXPECT_EQ(b.size(), 3u);
    }
    for (std::size_t i = 0; i < b.size(); ++i) {
      const std::uint32_t p = b[i], q = b[(i + 1) % b.size()];
      ++uses[{std::min(p, q), std::max(p, q)}];
    }
  }
  std::size_t inside_grain_edges = 0, grain_boundary_edges = 0;
  const auto on_outline = [&](geometry::Point p) {
    return std::min({p.x, p.y, side - p.x, side - p.y}) < 1e-12;
  };
  for (const auto& [edge, n] : uses) {
    const geometry::Point a = t.vertices[edge.first], b = t.vertices[edge.second];
    if (n == 1) {
      EXPECT_TRUE(on_outline(a) && on_outline(b)) << a.x << "," << a.y << " " << b.x << "," << b.y;
    } else {
      EXPECT_EQ(n, 2);
    }
  }
  // Both kinds of shared edge exist: inside grains and between grains.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::int32_t>> grains_of;
  for (std::size_t k = 0; k < t.blocks.size(); ++k)
    for (std::size_t i = 0; i < t.blocks[k].size(); ++i) {
      const std::uint32_t p = t.blocks[k][i], q = t.blocks[k][(i + 1) % t.blocks[k].size()];
      grains_of[{std::min(p, q), std::max(p, q)}].push_back(t.block_grain[k]);
    }
  for (const auto& [edge, grains] : grains_of)
    if (grains.size() == 2) ++(grains[0] == grains[1] ? inside_grain_edges : grain_boundary_edges);
  EXPECT_GT(inside_grain_edges, 0u);
  EXPECT_GT(grain_boundary_edges, 0u);
}

TEST(Grains, VoronoiSubBlocksShareEveryGrainBoundaryVertex) {
  EXPECT_NO_FATAL_FAILURE(expect_matching_edges(geometry::SubBlocks::voronoi));
}

TEST(Grains, TrigonSubBlocksAreTrianglesSharingEveryGrainBoundaryVertex) {
  EXPECT_NO_FATAL_FAILURE(expect_matching_edges(geometry::SubBlocks::trigon));
}

// Contacts inside one grain use the transgranular law group, contacts between grains the
// intergranular one, and quartz-feldspar boundaries their own pair law.
TEST(Grains, ContactsKnowWhetherTheyCrossAGrainBoundary) {
  const io::ModelConfig cfg = run::read_model_file(kSmall);
  const geometry::Tessellation t = run::make_specimen(cfg);
  const run::PreparedModel p = run::prepare_model(cfg, t);
  std::map<int, std::size_t> per_law;
  for (const model::Contact& c : p.model->contacts) {
    const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
    if (a >= t.block_grain.size() || b >= t.block_grain.size()) {
      EXPECT_EQ(c.law, 1);  // platens
      continue;
    }
    const std::int32_t ga = t.block_grain[a], gb = t.block_grain[b];
    const std::int32_t ma = t.grain_mineral[static_cast<std::size_t>(ga)];
    const std::int32_t mb = t.grain_mineral[static_cast<std::size_t>(gb)];
    // Law groups: 0 intergranular, 1 platens, 2 transgranular, 3 the quartz-feldspar pair.
    const int expected = ga == gb ? 2 : (ma != mb ? 3 : 0);
    EXPECT_EQ(c.law, expected) << "blocks " << a << " " << b;
    ++per_law[c.law];
  }
  for (const int law : {0, 2, 3}) EXPECT_GT(per_law[law], 0u) << "law " << law;
  // Forces scale with the contact length: tension force / normal stiffness = tension / jkn.
  const auto ratio = [&](int law) {
    const auto v = p.solver->laws()[static_cast<std::size_t>(law)]->properties(0);
    return v[2] / v[0];  // "tension_force [N]" / "kn [N/m]"
  };
  EXPECT_DOUBLE_EQ(ratio(3), 6e6 / 2e13);   // the quartz-feldspar pair's own tension
  EXPECT_DOUBLE_EQ(ratio(0), 8e6 / 2e13);   // intergranular
  EXPECT_DOUBLE_EQ(ratio(2), 16e6 / 4e13);  // transgranular
}

fs::path write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
  return file;
}

std::string grain_file_model(const std::string& grain_file) {
  const std::string text = slurp(kSmall);
  const auto begin = text.find("width = 0.01"), end = text.find("sub_blocks = ");
  std::string model = text.substr(0, begin);
  // Without the short-edge collapse the grains keep their exact areas.
  model.append("grain_file = '").append(grain_file).append("'\n").append(text.substr(end));
  model.replace(model.find("min_edge_length = 1e-4"), 22, "min_edge_length = 0");
  return model;
}

TEST(Grains, GrainFileGivesTheTracedGrainsAndTheirMinerals) {
  const fs::path dir = vorodec::testing::out_dir("grain_file");
  // Four 5 x 5 mm squares (two quartz), corners listed clockwise for one of them.
  write(dir / "grains.csv",
        "grain_id,mineral,x,y\n# traced\n"
        "g1,feldspar,0,0\ng1,feldspar,0.005,0\ng1,feldspar,0.005,0.005\ng1,feldspar,0,0.005\n"
        "g2,quartz,0.005,0\ng2,quartz,0.01,0\ng2,quartz,0.01,0.005\ng2,quartz,0.005,0.005\n"
        "g3,quartz,0,0.005\ng3,quartz,0,0.01\ng3,quartz,0.005,0.01\ng3,quartz,0.005,0.005\n"
        "g4,feldspar,0.005,0.005\ng4,feldspar,0.01,0.005\ng4,feldspar,0.01,0.01\n"
        "g4,feldspar,0.005,0.01\n");
  const fs::path model = write(dir / "model.toml", grain_file_model("grains.csv"));
  const io::ModelConfig cfg = run::read_model_file(model);
  const geometry::Tessellation t = run::make_specimen(cfg);
  EXPECT_EQ(t.grain_mineral, (std::vector<std::int32_t>{0, 1, 1, 0}));
  ASSERT_EQ(t.mineral_area.size(), 2u);
  EXPECT_NEAR(t.mineral_area[0], 50e-6, 1e-12);  // m^2
  EXPECT_NEAR(t.mineral_area[1], 50e-6, 1e-12);
  EXPECT_GT(t.blocks.size(), 4u * 15u);  // 25 mm^2 grains of ~1.1 mm^2 sub-blocks
  EXPECT_EQ(run_capture("check " + model.string()).code, 0);
}

TEST(Grains, BadGrainFileGivesFileLineAndExitCode2) {
  const fs::path dir = vorodec::testing::out_dir("bad_grain_file");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"g1,feldspar,0,0\ng1,feldspar,0.005,0\ng1,granite,0.005,0.005\n", ":3: unknown mineral"},
      {"g1,feldspar,0,0\ng1,feldspar,0.005,zero\n", ":2: x and y must be numbers"},
      {"g1,feldspar,0,0\ng1,feldspar,0.005,0\ng2,quartz,0,0\n", ":1: grain 'g1' has fewer than 3"},
      {"g1,feldspar,0,0\ng1,feldspar,0.01,0.005\ng1,feldspar,0.01,0\ng1,feldspar,0,0.01\n",
       ":1: grain 'g1': its boundary crosses itself"}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string name = "bad" + std::to_string(i) + ".csv";
    write(dir / name, cases[i].first);
    const fs::path model =
        write(dir / ("model" + std::to_string(i) + ".toml"), grain_file_model(name));
    const auto o = run_capture("check " + model.string());
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find(name + cases[i].second), std::string::npos) << o.output;
  }
}

TEST(Grains, CrackClassesSumToTheCrackCountInHistorySummaryAndCrackList) {
  const fs::path out = vorodec::testing::out_dir("grain_run");
  ASSERT_EQ(vorodec::testing::run_vorodec("run " + kSmall.string() + " --threads 1 --out " +
                                          out.string()),
            0);
  const std::string json = slurp(out / "summary.json");
  const double tensile = json_number(json, "tensile"), shear = json_number(json, "shear");
  ASSERT_GT(tensile + shear, 20);
  // Classes in summary.json: "crack_classes": {"<class>": {"count": n, ...}, ...}.
  const vorodec::io::Json summary = vorodec::io::Json::parse(json);
  double classes = 0;
  for (const auto name : measure::kCrackClassNames) {
    ASSERT_TRUE(summary.at("crack_classes").contains(name)) << name;
    classes += summary["crack_classes"][std::string(name)]["count"].get<double>();
  }
  EXPECT_EQ(classes, tensile + shear);
  // history.csv: the last row's class counts (columns 17-20) sum to its tensile + shear (6, 7).
  const auto rows = read_csv(out / "history.csv");
  const auto& last = rows.back();
  ASSERT_GE(last.size(), 25u);
  EXPECT_EQ(last[17] + last[18] + last[19] + last[20], last[6] + last[7]);
  EXPECT_EQ(last[17] + last[19], last[6]);  // tensile classes
  // cracks.csv: one row per crack with its class 1-4 (column 7).
  const auto cracks = read_csv(out / "cracks.csv");
  ASSERT_EQ(static_cast<double>(cracks.size()), tensile + shear);
  std::vector<double> per_class(4, 0.0);
  for (const auto& c : cracks) per_class[static_cast<std::size_t>(c[7]) - 1] += 1;
  EXPECT_EQ(per_class[0], last[17]);
  EXPECT_EQ(per_class[3], last[20]);
}

}  // namespace

namespace {

TEST(Grains, BadGrainKeysNameFileLineAndKey) {
  const fs::path dir = vorodec::testing::out_dir("bad_grain_keys");
  const std::string text = slurp(kSmall);
  const std::vector<std::pair<std::pair<std::string, std::string>, std::string>> cases = {
      {{"fraction = 0.4", "fraction = 0.3"},
       ":15: key 'mineral': the minerals' fractions sum to 0.9 "},
      {{"[joints.pair.\"quartz-feldspar\"]", "[joints.pair.\"quartz-mica\"]"},
       "key 'joints.pair.quartz-mica': must name two minerals"},
      {{"sub_blocks = \"voronoi\"", "sub_blocks = \"squares\""}, ":11: key 'specimen.sub_blocks'"},
      {{"[joints.transgranular]", "[joints.transgranularr]"}, "key 'joints.transgranular'"},
      // A pair's law is read over the intergranular table in place: its values keep their line.
      {{"tension = 6e6", "tension = -6e6"},
       ":40: key 'joints.pair.quartz-feldspar.tension': must be >= 0"},
      {{"grain_size = 2.5e-3", "grain_size = 1e-300"}, ":10: key 'specimen.grain_size': must be "},
      {{"sub_block_size = 1.2e-3", "sub_block_size = 1e-5"},
       ":12: key 'specimen.sub_block_size': gives about"}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::string model = text;
    const auto& [from, to] = cases[i].first;
    model.replace(model.find(from), from.size(), to);
    std::string name = std::to_string(i);
    name += ".toml";
    const fs::path file = write(dir / name, model);
    const auto o = run_capture("check " + file.string());
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find(cases[i].second), std::string::npos) << o.output;
  }
}

}  // namespace

namespace {

std::string deformable_grains_model() {
  std::string text = slurp(kSmall);
  text.replace(text.find("density = 2610             # kg/m^3"), 35,
               "density = 2610\nE = 70e9\nnu = 0.28");
  text.replace(text.find("density = 2650             # kg/m^3"), 35,
               "density = 2650\nE = 95e9\nnu = 0.08");
  text.replace(text.find("[[mineral]]"), 11,
               "[blocks]\ndeformable = true\nzone_size = 1e-3\n\n[[mineral]]");
  return text;
}

}  // namespace

// Deformable grain-based specimens: each zone is as stiff as its grain's mineral.
TEST(Grains, DeformableGrainsTakeTheirMineralsElasticity) {
  const fs::path dir = vorodec::testing::out_dir("deformable_grains");
  const fs::path model = write(dir / "model.toml", deformable_grains_model());
  const io::ModelConfig cfg = run::read_model_file(model);
  const geometry::Tessellation t = run::make_specimen(cfg);
  const run::PreparedModel p = run::prepare_model(cfg, t);
  const model::Zoning& z = p.model->zoning;
  ASSERT_FALSE(z.empty());
  std::size_t per_mineral[2] = {0, 0};
  for (std::size_t i = 0; i < z.zones.size(); ++i) {
    const std::size_t block = z.zone_block[i];
    const auto m =
        static_cast<std::size_t>(t.grain_mineral[static_cast<std::size_t>(t.block_grain[block])]);
    const double e = m == 0 ? 70e9 : 95e9, nu = m == 0 ? 0.28 : 0.08;
    EXPECT_DOUBLE_EQ(z.zones[i].shear, e / (2 * (1 + nu))) << "zone " << i;
    ++per_mineral[m];
  }
  EXPECT_GT(per_mineral[0], 0u);
  EXPECT_GT(per_mineral[1], 0u);
}

TEST(Grains, DeformableGrainsNeedEveryMineralsElasticity) {
  const fs::path dir = vorodec::testing::out_dir("deformable_grains_bad");
  std::string text = deformable_grains_model();
  text.replace(text.find("E = 95e9\nnu = 0.08"), 18, "");
  const auto missing = run_capture("check " + write(dir / "missing.toml", text).string());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("'quartz' has none"), std::string::npos) << missing.output;
  text = deformable_grains_model();
  text.replace(text.find("deformable = true"), 17, "deformable = true\ndensity = 2600");
  const auto density = run_capture("check " + write(dir / "density.toml", text).string());
  EXPECT_EQ(density.code, 2);
  EXPECT_NE(density.output.find("key 'blocks.density'"), std::string::npos) << density.output;
}
