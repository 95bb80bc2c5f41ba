// The contact loop's thread parts (laws::StepContext::cuts): blocks of one part get their force
// sums in the loop, blocks shared by parts get them gathered afterwards, both in contact order.
// Contact detection cuts the block pairs into runs, one per thread, joined in pair order. The
// energy the contacts dissipate is summed in contact order too. So the run must be the same bits,
// and the same contacts in the same order, however many parts there are and wherever they are cut
// (the solver cuts them by measured time, solver/part_balance.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include <string>
#include <vector>

#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/solver/part_balance.hpp"

using namespace vorodec;

namespace {

struct Snapshot {
  std::vector<double> x, y, theta, vx, vy, omega, fn, fs;
  std::vector<std::uint64_t> id;
  std::vector<std::uint32_t> corner, edge;
  double slip, breakage, viscous;  // J per m dissipated
};

// `shares`: the parts' shares of every contact pass, pinned; empty: cut by measured time.
Snapshot run_with_parts(const std::string& model_file, double platen_velocity, int parts,
                        const std::vector<double>& shares = {}) {
  omp_set_num_threads(parts);
  io::ModelConfig cfg =
      run::read_model_file(std::string(VORODEC_SOURCE_DIR) + "/tests/models/" + model_file);
  // Enough blocks for the contact loop to open its parallel region (>= 2,048 contacts).
  cfg.tessellation.block_count = 600;
  cfg.tessellation.outline.width *= 2.0;
  cfg.tessellation.outline.height *= 2.0;
  const auto specimen = run::make_specimen(cfg);
  run::PreparedModel pm = run::prepare_model(cfg, specimen);
  const loading::SpecimenBoundary boundary(*pm.model);
  boundary.set_platen_velocity(*pm.model, platen_velocity);
  if (!shares.empty()) pm.solver->pin_part_shares(shares);
  for (int i = 0; i < 400; ++i) pm.solver->step();
  omp_set_num_threads(1);
  const model::Blocks& bl = pm.model->blocks;
  const solver::Energy& e = pm.solver->energy();
  Snapshot s{bl.x, bl.y, bl.theta, bl.vx, bl.vy,  bl.omega,   {},
             {},   {},   {},       {},    e.slip, e.breakage, e.viscous};
  for (const auto& c : pm.model->contacts) {
    s.fn.push_back(c.fn);
    s.fs.push_back(c.fs);
    s.id.push_back(c.id);
    s.corner.push_back(c.corner);
    s.edge.push_back(c.edge);
  }
  // The run redetected contacts after its initial detection (at most every 200 steps).
  EXPECT_GE(pm.solver->detections(), 2u);
  return s;
}

void expect_same(const Snapshot& many, const Snapshot& one, int parts) {
  // EXPECT_EQ on doubles compares exactly: any change of summation order would show.
  EXPECT_EQ(many.x, one.x) << parts << " parts";
  EXPECT_EQ(many.y, one.y) << parts << " parts";
  EXPECT_EQ(many.theta, one.theta) << parts << " parts";
  EXPECT_EQ(many.vx, one.vx) << parts << " parts";
  EXPECT_EQ(many.vy, one.vy) << parts << " parts";
  EXPECT_EQ(many.omega, one.omega) << parts << " parts";
  EXPECT_EQ(many.fn, one.fn) << parts << " parts";
  EXPECT_EQ(many.fs, one.fs) << parts << " parts";
  EXPECT_EQ(many.id, one.id) << parts << " parts";
  EXPECT_EQ(many.corner, one.corner) << parts << " parts";
  EXPECT_EQ(many.edge, one.edge) << parts << " parts";
  EXPECT_EQ(many.slip, one.slip) << parts << " parts";
  EXPECT_EQ(many.breakage, one.breakage) << parts << " parts";
  EXPECT_EQ(many.viscous, one.viscous) << parts << " parts";
}

// Returns the one-part run.
Snapshot expect_same_for_three_and_four_parts(const std::string& model_file,
                                              double platen_velocity) {
  const Snapshot one = run_with_parts(model_file, platen_velocity, 1);
  for (const int parts : {3, 4})
    expect_same(run_with_parts(model_file, platen_velocity, parts), one, parts);
  return one;
}

}  // namespace

TEST(ThreadParts, BlocksContactsAndTheirForcesAreTheSameForOneThreeAndFourParts) {
  const Snapshot one = expect_same_for_three_and_four_parts("e2e_small.toml", 0.05);
  // Enough contacts for the contact loop's parallel region, or the parts never run apart.
  EXPECT_GE(one.fn.size(), 2048u);
}

TEST(ThreadParts, DissipatedEnergiesAreTheSameForOneThreeAndFourParts) {
  // Fast enough that contacts break and slip within the 400 steps; Burger's dashpots work in
  // every step.
  const Snapshot cracking = expect_same_for_three_and_four_parts("e2e_small.toml", 2.0);
  EXPECT_GE(cracking.fn.size(), 2048u);
  EXPECT_GT(cracking.slip, 0.0);
  EXPECT_GT(cracking.breakage, 0.0);
  const Snapshot creeping = expect_same_for_three_and_four_parts("creep_burgers_small.toml", 2.0);
  EXPECT_GE(creeping.fn.size(), 2048u);
  EXPECT_GT(creeping.viscous, 0.0);
}

TEST(ThreadParts, UnequalPartsGiveTheSameBitsForRigidAndDeformableContacts) {
  // Cracking and slipping rigid contacts, then deformable ones, each cut into lopsided parts.
  for (const char* model : {"e2e_small.toml", "deformable_small.toml"}) {
    const Snapshot one = run_with_parts(model, 2.0, 1);
    EXPECT_GE(one.fn.size(), 2048u) << model;
    EXPECT_GT(one.breakage, 0.0) << model;
    expect_same(run_with_parts(model, 2.0, 2, {0.15, 0.85}), one, 2);
    expect_same(run_with_parts(model, 2.0, 3, {0.6, 0.3, 0.1}), one, 3);
  }
}

TEST(ThreadParts, TheSlowerPartGetsFewerContactsAtTheNextCut) {
  solver::PartBalance balance;
  balance.reset(1, 2);
  const std::size_t* cuts = balance.cut(0, 100, 1100);
  EXPECT_EQ(cuts[1], 600u);  // equal shares to start with
  // Part 0 takes twice as long per contact as part 1, and both start together.
  balance.start(0);
  balance.clocks(0)[0] = {10.0, 12.0};
  balance.clocks(0)[1] = {10.0, 11.0};
  balance.record(0, 10.0);
  balance.rebalance();
  cuts = balance.cut(0, 100, 1100);
  // Equal finishing times would give part 0 a third; the cut moves halfway: 5/12 of 1,000.
  EXPECT_EQ(cuts[1], 100u + 417u);
  // A pass on one thread (clocks not written) is not a measure: the cut stays.
  balance.start(0);
  balance.record(0, 20.0);
  balance.rebalance();
  EXPECT_EQ(balance.cut(0, 100, 1100)[1], 517u);
}
