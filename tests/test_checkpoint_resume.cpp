// Checkpoint and resume: a run stopped and resumed writes the same files, byte for byte, as the
// same run never stopped; a kill at any moment leaves files that parse; bad checkpoints are
// refused with exit 2 and say why.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <thread>

#include "run_support.hpp"
#include "vorodec/checkpoint/checkpoint_file.hpp"

namespace {

using namespace vorodec::testing;

const std::string kModels = std::string(VORODEC_SOURCE_DIR) + "/tests/models/";
constexpr int kStopped = 6;

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir));
  std::sort(out.begin(), out.end());
  return out;
}

// summary.json without its wall time, which is the one value a resumed run may differ in.
std::string without_wall_time(const std::string& json) {
  std::string out;
  std::istringstream in(json);
  for (std::string line; std::getline(in, line);)
    if (line.find("\"wall_time_s\"") == std::string::npos) out += line + '\n';
  return out;
}

// Every file of `a` is in `b` with the same bytes (summary.json: but its wall time), and the
// other way round.
void expect_same_files(const fs::path& a, const fs::path& b) {
  const auto fa = files_under(a), fb = files_under(b);
  EXPECT_EQ(fa, fb);
  for (const fs::path& f : fa) {
    if (!fs::exists(b / f)) continue;
    if (f.filename() == "summary.json")
      EXPECT_EQ(without_wall_time(slurp(a / f)), without_wall_time(slurp(b / f))) << f;
    else
      EXPECT_TRUE(slurp(a / f) == slurp(b / f)) << f << " differs";
  }
}

// Runs `model` (with `extra` arguments) straight, then stopped at each of `stops` and resumed
// (alternating 1 and 2 threads), and compares the two results folders. `code`: the run's exit code.
void expect_resume_matches(const std::string& name, const std::string& model,
                           const std::vector<long>& stops, const std::string& extra = "",
                           int code = 0) {
  const fs::path straight = out_dir(name + "_straight"), stopped = out_dir(name + "_stopped");
  ASSERT_EQ(run_vorodec("run " + model + " --threads 1 --out " + straight.string() + extra), code);
  ASSERT_EQ(run_vorodec("run " + model + " --threads 1 --out " + stopped.string() + extra +
                        " --stop-at-step " + std::to_string(stops[0])),
            kStopped);
  EXPECT_TRUE(fs::exists(stopped / "checkpoint.vck"));
  EXPECT_FALSE(fs::exists(stopped / "summary.json"));
  for (std::size_t i = 1; i <= stops.size(); ++i) {
    const std::string threads = i % 2 ? " --threads 2" : " --threads 1";
    const std::string stop =
        i < stops.size() ? " --stop-at-step " + std::to_string(stops[i]) : std::string();
    ASSERT_EQ(run_vorodec("resume " + stopped.string() + threads + stop),
              i < stops.size() ? kStopped : code);
  }
  EXPECT_FALSE(fs::exists(stopped / "checkpoint.vck")) << "a finished run keeps no checkpoint";
  expect_same_files(straight, stopped);
}

TEST(Resume, RigidUcsStoppedInTheRampAndAfterThePeakMatchesTheUninterruptedRun) {
  // e2e_small: the platen ramps over the first 200 steps; the peak is near step 4000.
  expect_resume_matches("ucs", kModels + "e2e_small.toml", {150, 4300});
}

TEST(Resume, CyclicRunStoppedMidCycleMatchesTheUninterruptedRun) {
  expect_resume_matches("cyclic", kModels + "cyclic_small.toml", {3000, 9000, 15000});
}

TEST(Resume, GrainBasedDeformableRunMatchesTheUninterruptedRun) {
  // Zoned grains; the run ends unstable after its peak (step 8100), so the restore of the last
  // good state is resumed too.
  expect_resume_matches("grains_deformable", kModels + "grains_small.toml", {700, 2500, 6000},
                        " --set blocks.deformable=true --set blocks.zone_size=1e-3"
                        " --set 'mineral[0].E=60e9' --set 'mineral[0].nu=0.25'"
                        " --set 'mineral[1].E=90e9' --set 'mineral[1].nu=0.1'",
                        3);
}

TEST(Resume, DeformableRunMatchesTheUninterruptedRun) {
  expect_resume_matches("deformable", kModels + "deformable_small.toml", {1200, 3000});
}

}  // namespace
