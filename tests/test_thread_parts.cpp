// The contact loop's thread parts (laws::chunk_range): blocks of one part get their force sums in
// the loop, blocks shared by parts get them gathered afterwards, both in contact order. Contact
// detection cuts the block pairs into runs, one per thread, joined in pair order. So the run must
// be the same bits, and the same contacts in the same order, however many parts there are.
#include <gtest/gtest.h>
#include <omp.h>

#include <string>
#include <vector>

#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"

using namespace vorodec;

namespace {

struct Snapshot {
  std::vector<double> x, y, theta, vx, vy, omega, fn, fs;
  std::vector<std::uint64_t> id;
  std::vector<std::uint32_t> corner, edge;
};

Snapshot run_with_parts(int parts) {
  omp_set_num_threads(parts);
  io::ModelConfig cfg =
      run::read_model_file(std::string(VORODEC_SOURCE_DIR) + "/tests/models/e2e_small.toml");
  // Enough blocks for the contact loop to open its parallel region (>= 2,048 contacts).
  cfg.tessellation.block_count = 600;
  cfg.tessellation.outline.width *= 2.0;
  cfg.tessellation.outline.height *= 2.0;
  const auto specimen = run::make_specimen(cfg);
  run::PreparedModel pm = run::prepare_model(cfg, specimen);
  const loading::SpecimenBoundary boundary(*pm.model);
  boundary.set_platen_velocity(*pm.model, 0.05);
  for (int i = 0; i < 400; ++i) pm.solver->step();
  omp_set_num_threads(1);
  const model::Blocks& bl = pm.model->blocks;
  Snapshot s{bl.x, bl.y, bl.theta, bl.vx, bl.vy, bl.omega, {}, {}, {}, {}, {}};
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

}  // namespace

TEST(ThreadParts, BlocksContactsAndTheirForcesAreTheSameForOneThreeAndFourParts) {
  const Snapshot one = run_with_parts(1);
  ASSERT_GE(one.fn.size(), 2048u);
  for (const int parts : {3, 4}) {
    const Snapshot many = run_with_parts(parts);
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
  }
}
