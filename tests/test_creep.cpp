// Burger's creep through the real command: creep stages hold sigma1 - sigma3 while the specimen
// creeps at a falling rate, time is told in days, the energy balance closes with the dashpots'
// work; and the random split of joints between two laws ([Guo2020]'s reading (b)).
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "run_support.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"

using namespace vorodec;
using namespace vorodec::testing;

namespace {

const fs::path kSmall = fs::path(VORODEC_SOURCE_DIR) / "tests/models/creep_burgers_small.toml";

// history.csv as columns by name; the stage label (last column) as text.
struct History {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  std::vector<std::string> stages;
  double at(std::size_t row, const std::string& name) const {
    const auto i = std::find(names.begin(), names.end(), name) - names.begin();
    return rows[row][static_cast<std::size_t>(i)];
  }
};

History read_history(const fs::path& file) {
  History h;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::stringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');) h.names.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<double> row;
    std::string cell;
    for (std::size_t i = 0; i + 1 < h.names.size() && std::getline(ss, cell, ','); ++i)
      row.push_back(std::atof(cell.c_str()));
    std::getline(ss, cell);
    h.rows.push_back(row);
    h.stages.push_back(cell);
  }
  return h;
}

const fs::path& creep_run() {
  static const fs::path out = [] {
    const fs::path o = out_dir("creep_small");
    EXPECT_EQ(run_vorodec("run " + kSmall.string() + " --threads 1 --no-vtk --out " + o.string()),
              0);
    return o;
  }();
  return out;
}

}  // namespace

TEST(Creep, StagesHoldTheDeviatoricStressWhileTheSpecimenCreepsEverSlower) {
  const History h = read_history(creep_run() / "history.csv");
  for (const auto& [stage, deviatoric] : {std::pair{"creep20", 20e6}, std::pair{"creep30", 30e6}}) {
    std::vector<std::size_t> rows;
    for (std::size_t r = 0; r < h.rows.size(); ++r)
      if (h.stages[r] == stage) rows.push_back(r);
    ASSERT_GT(rows.size(), 20u) << stage;
    const double t0 = h.at(rows.front(), "time"), t1 = h.at(rows.back(), "time");
    std::size_t held = 0;
    for (const std::size_t r : rows)
      if (h.at(r, "time") - t0 > 0.1 * (t1 - t0)) {
        EXPECT_NEAR(h.at(r, "axial_stress"), 5e6 + deviatoric, 0.01 * (5e6 + deviatoric)) << stage;
        ++held;
      }
    EXPECT_GT(held, 10u);
    // Kelvin creep (Ck/Kk = 100 s): the strain grows, more in the first third than the last.
    const auto strain_at = [&](double t) {
      std::size_t best = rows.front();
      for (const std::size_t r : rows)
        if (std::abs(h.at(r, "time") - t) < std::abs(h.at(best, "time") - t)) best = r;
      return h.at(best, "axial_strain");
    };
    const double span = t1 - t0;
    const double first = strain_at(t0 + span / 3) - strain_at(t0 + 0.05 * span);
    const double last = strain_at(t1) - strain_at(t1 - span / 3);
    EXPECT_GT(first, 0.0) << stage;
    EXPECT_GT(last, 0.0) << stage;
    EXPECT_GT(first, 1.5 * last) << stage;
  }
  for (std::size_t r = 0; r < h.rows.size(); ++r)
    EXPECT_NEAR(h.at(r, "time_days"), h.at(r, "time") / 86400.0, 1e-9 * h.at(r, "time") / 86400.0);
}

TEST(Creep, EnergyBalanceClosesWithTheDashpotsWork) {
  const History h = read_history(creep_run() / "history.csv");
  const std::size_t last = h.rows.size() - 1;
  const double supplied = h.at(last, "boundary_work");
  double held = 0;
  for (const char* term : {"strain_energy", "kinetic_energy", "damping_energy", "friction_energy",
                           "breakage_energy", "viscous_energy"})
    held += h.at(last, term);
  EXPECT_GT(h.at(last, "viscous_energy"), 0.0);
  EXPECT_NEAR(held, supplied, 0.01 * supplied);
}

TEST(Creep, SummaryReportsEachCreepStageStepsAndQuasiStaticState) {
  const std::string json = slurp(creep_run() / "summary.json");
  for (const char* stage : {"\"stage\": \"creep20\"", "\"stage\": \"creep30\""})
    EXPECT_NE(json.find(stage), std::string::npos) << json;
  EXPECT_NE(json.find("\"max_kinetic_over_strain_energy\""), std::string::npos);
  EXPECT_NE(json.find("\"collapse_days\": null"), std::string::npos) << "no creep failure here";
}

TEST(Creep, AMixFractionOfJointsTakesTheSecondLawWholeJointsAtATime) {
  io::ModelConfig cfg = run::read_model_file(kSmall);
  io::LawChoice mc{"mohr_coulomb", {}};
  for (const char* k : {"jkn", "jks"}) mc.params[k] = model::Distribution::constant(1e13);
  for (const char* k : {"tension", "cohesion", "friction", "dilation"})
    mc.params[k] = model::Distribution::constant(k[0] == 'f' ? 30.0 : 1e7);
  cfg.joint_mix = io::ModelConfig::JointMix{0.3, mc};
  const geometry::Tessellation t = run::make_specimen(cfg);
  const run::PreparedModel p = run::prepare_model(cfg, t);
  std::map<std::pair<int, int>, std::set<int>> laws_of_joint;
  for (const model::Contact& c : p.model->contacts)
    if (c.law != 1) laws_of_joint[{std::min(c.a, c.b), std::max(c.a, c.b)}].insert(c.law);
  std::size_t mixed = 0;
  for (const auto& [joint, laws] : laws_of_joint) {
    EXPECT_EQ(laws.size(), 1u) << "a joint's point contacts share one law";
    mixed += laws.count(2);
  }
  const double share = double(mixed) / double(laws_of_joint.size());
  EXPECT_NEAR(share, 0.3, 0.05) << laws_of_joint.size() << " joints";
  EXPECT_EQ(p.solver->laws()[2]->name(), "mohr_coulomb");
  EXPECT_TRUE(p.solver->viscous());
}

TEST(Creep, ASpecimenThatGivesWayUnderItsCreepLoadReportsCreepFailureAndItsTime) {
  // The second creep stage asks for 120 MPa, far above the small specimen's strength.
  const fs::path out = out_dir("creep_collapse");
  ASSERT_EQ(run_vorodec("run " + kSmall.string() + " --threads 1 --no-vtk --out " + out.string() +
                        " --set 'stage[2].deviatoric_stress=120e6'"),
            3);
  const std::string json = slurp(out / "summary.json");
  EXPECT_NE(json.find("creep failure in stage 'creep30'"), std::string::npos) << json;
  const auto number_after = [&](const std::string& key) {
    const auto pos = json.rfind("\"" + key + "\": ");
    return pos == std::string::npos ? std::nan("")
                                    : std::strtod(json.c_str() + pos + key.size() + 4, nullptr);
  };
  const double collapse = number_after("collapse_days"), onset = number_after("failure_onset_days");
  EXPECT_GT(collapse, 0.0);
  EXPECT_LT(collapse, 300.0 / 86400.0);
  EXPECT_LE(onset, collapse);
}
