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
  EXPECT_NO_FATAL_FAILURE(expect_resume_matches("ucs", kModels + "e2e_small.toml", {150, 4300}));
}

TEST(Resume, CyclicRunStoppedMidCycleMatchesTheUninterruptedRun) {
  EXPECT_NO_FATAL_FAILURE(
      expect_resume_matches("cyclic", kModels + "cyclic_small.toml", {3000, 9000, 15000}));
}

TEST(Resume, GrainBasedDeformableRunMatchesTheUninterruptedRun) {
  // Zoned grains; the run ends unstable after its peak (step 8100), so the restore of the last
  // good state is resumed too.
  EXPECT_NO_FATAL_FAILURE(
      expect_resume_matches("grains_deformable", kModels + "grains_small.toml", {700, 2500, 6000},
                            " --set blocks.deformable=true --set blocks.zone_size=1e-3"
                            " --set 'mineral[0].E=60e9' --set 'mineral[0].nu=0.25'"
                            " --set 'mineral[1].E=90e9' --set 'mineral[1].nu=0.1'",
                            3));
}

TEST(Resume, CorrosionStageStoppedMidFatigueMatchesTheUninterruptedRun) {
  // corrosion_small: corrosion steps from step ~2000 to 23590, then no equilibrium: the collapse
  // ends the run at step 43590; the stops fall between corrosion steps (9020), in an equilibrium
  // (9030) and in the collapse.
  EXPECT_NO_FATAL_FAILURE(expect_resume_matches("corrosion", kModels + "corrosion_small.toml",
                                                {9020, 9030, 30000, 43000}));
}

TEST(Resume, PressureBarTestStoppedMidImpactMatchesTheUninterruptedRun) {
  // shpb_small: 885 steps; the stops fall before and after the peak (step ~650).
  EXPECT_NO_FATAL_FAILURE(expect_resume_matches("shpb", kModels + "shpb_small.toml", {300, 700}));
}

TEST(Resume, ExcavationStoppedBeforeAndAfterTheBlocksGoMatchesTheUninterruptedRun) {
  // tunnel_small: in-situ stress for 1000 steps, then the excavation (3002 steps in all).
  EXPECT_NO_FATAL_FAILURE(
      expect_resume_matches("excavation", kModels + "tunnel_small.toml", {900, 1500, 2500}));
}

TEST(Resume, InSituStartStoppedWhileItHoldsMatchesTheUninterruptedRun) {
  // in_situ_small: contacts preloaded before the first step (the energy term 'initial' too).
  EXPECT_NO_FATAL_FAILURE(
      expect_resume_matches("in_situ", kModels + "in_situ_small.toml", {300, 700}));
}

TEST(Resume, ZonedInSituStartMatchesTheUninterruptedRun) {
  // The zones' in-situ stress comes again from the model file.
  EXPECT_NO_FATAL_FAILURE(expect_resume_matches(
      "in_situ_zoned", kModels + "in_situ_small.toml", {300, 1500},
      " --set blocks.deformable=true --set blocks.zone_size=0.05 --set blocks.E=30e9"
      " --set blocks.nu=0.25"));
}

TEST(Resume, DeformableRunMatchesTheUninterruptedRun) {
  EXPECT_NO_FATAL_FAILURE(
      expect_resume_matches("deformable", kModels + "deformable_small.toml", {1200, 3000}));
}

}  // namespace

namespace {

// The lines of a text file.
std::vector<std::string> lines_of(const fs::path& f) {
  std::vector<std::string> out;
  std::istringstream in(slurp(f));
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::size_t fields(const std::string& line) {
  return static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Every file a run left in `dir` parses: CSV files hold whole rows of the header's width, VTK
// files are complete XML, .pvd collections name frames that exist, summary.json is whole.
void expect_parseable(const fs::path& dir) {
  for (const fs::path& rel : files_under(dir)) {
    const fs::path f = dir / rel;
    const std::string text = slurp(f);
    const std::string ext = f.extension().string();
    if (ext == ".csv") {
      EXPECT_TRUE(ends_with(text, "\n")) << rel << " ends in a partial row";
      const auto lines = lines_of(f);
      ASSERT_FALSE(lines.empty()) << rel;
      for (const std::string& l : lines) EXPECT_EQ(fields(l), fields(lines[0])) << rel << ": " << l;
    } else if (ext == ".vtp" || ext == ".vti" || ext == ".pvd") {
      EXPECT_TRUE(text.rfind("<?xml", 0) == 0 || text.rfind("<VTKFile", 0) == 0) << rel;
      EXPECT_TRUE(ends_with(text, "</VTKFile>\n")) << rel << " is not whole";
      if (ext == ".pvd")
        for (std::size_t at = text.find("file=\""); at != std::string::npos;
             at = text.find("file=\"", at + 1)) {
          const auto begin = at + 6;
          const std::string name = text.substr(begin, text.find('"', begin) - begin);
          EXPECT_TRUE(fs::exists(f.parent_path() / name)) << rel << " names " << name;
        }
    } else if (rel == "summary.json") {
      EXPECT_EQ(text.rfind("{", 0), 0u);
      EXPECT_TRUE(ends_with(text, "}\n")) << "summary.json is not whole";
    }
  }
}

// Starts `vorodec <args>` and returns its pid.
pid_t start_vorodec(const std::string& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec " + std::string(VORODEC_BINARY) + " " + args + " >/dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

void kill_hard(pid_t pid) {
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
}

// The marble UCS model, short, with a checkpoint every 1000 steps and frames every 1000.
std::string marble_args(const fs::path& out) {
  return std::string(VORODEC_SOURCE_DIR) + "/models/ucs_marble.toml --threads 1 --max-steps 6000" +
         " --set output.checkpoint_steps=1000 --set output.vtk_steps=1000 --out " + out.string();
}

}  // namespace

TEST(KilledRun, LeavesOnlyFilesThatParseAtAnyMoment) {
  for (const int ms : {300, 1200, 2500, 4000}) {
    const fs::path out = out_dir("killed_" + std::to_string(ms));
    const pid_t pid = start_vorodec("run " + marble_args(out));
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    kill_hard(pid);
    if (fs::exists(out)) {  // a kill before the folder is made leaves nothing to parse
      EXPECT_NO_FATAL_FAILURE(expect_parseable(out));
    }
  }
}

TEST(KilledRun, ResumesFromItsLastCheckpointToTheUninterruptedResult) {
  const fs::path straight = out_dir("kill_straight"), killed = out_dir("kill_resumed");
  ASSERT_EQ(run_vorodec("run " + marble_args(straight)), 0);
  const pid_t pid = start_vorodec("run " + marble_args(killed));
  // Killed once a checkpoint exists and the run has gone on past it.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!fs::exists(killed / "checkpoint.vck") && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill_hard(pid);
  EXPECT_NO_FATAL_FAILURE(expect_parseable(killed));
  ASSERT_TRUE(fs::exists(killed / "checkpoint.vck")) << "the run ended before it was killed";
  EXPECT_EQ(run_vorodec("resume " + killed.string()), 0);
  expect_same_files(straight, killed);
}

namespace {

// A run of e2e_small stopped at step 1000, its checkpoint ready to be spoilt.
fs::path stopped_run(const std::string& name, const std::string& model) {
  const fs::path out = out_dir(name);
  EXPECT_EQ(run_vorodec("run " + model + " --threads 1 --no-vtk --stop-at-step 1000 --out " +
                        out.string()),
            kStopped);
  return out;
}

void expect_refused(const fs::path& dir, const std::string& why) {
  const Outcome o = run_capture("resume " + dir.string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(why), std::string::npos) << o.output;
}

}  // namespace

TEST(ResumeRefuses, AFolderWithoutACheckpoint) {
  const fs::path out = out_dir("no_checkpoint");
  fs::create_directories(out);
  EXPECT_NO_FATAL_FAILURE(expect_refused(out, "no checkpoint there"));
}

TEST(ResumeRefuses, ATruncatedCheckpoint) {
  const fs::path out = stopped_run("truncated", kModels + "e2e_small.toml");
  const fs::path f = out / "checkpoint.vck";
  fs::resize_file(f, fs::file_size(f) / 2);
  EXPECT_NO_FATAL_FAILURE(expect_refused(out, "truncated"));
}

TEST(ResumeRefuses, ACorruptCheckpoint) {
  const fs::path out = stopped_run("corrupt", kModels + "e2e_small.toml");
  const fs::path f = out / "checkpoint.vck";
  std::string bytes = slurp(f);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x5a);
  std::ofstream(f, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_NO_FATAL_FAILURE(expect_refused(out, "corrupt"));
}

TEST(ResumeRefuses, AFileThatIsNoCheckpoint) {
  const fs::path out = out_dir("not_checkpoint");
  fs::create_directories(out);
  std::ofstream(out / "checkpoint.vck") << "history,of,something\n1,2,3\n";
  EXPECT_NO_FATAL_FAILURE(expect_refused(out, "not a vorodec checkpoint"));
}

TEST(ResumeRefuses, ARunWhoseModelFileChanged) {
  const fs::path dir = out_dir("changed_model");
  fs::create_directories(dir);
  const fs::path model = dir / "model.toml";
  fs::copy_file(kModels + "e2e_small.toml", model);
  const fs::path out = stopped_run("changed_model/out", model.string());
  std::ofstream(model, std::ios::app) << "# edited\n";
  EXPECT_NO_FATAL_FAILURE(expect_refused(out, "changed since the checkpoint"));
}

TEST(ResumeRefuses, ACheckpointOfAnotherVorodecVersion) {
  const fs::path out = out_dir("other_version");
  fs::create_directories(out);
  vorodec::checkpoint::Header h;
  h.vorodec_version = "0.0.1-elsewhere";
  vorodec::checkpoint::write_checkpoint(out / "checkpoint.vck", h, [](auto&) {});
  EXPECT_NO_FATAL_FAILURE(expect_refused(out, "written by vorodec 0.0.1-elsewhere"));
}

TEST(BatchRunAgain, KeepsFinishedCasesResumesStoppedOnesAndRunsMissingOnes) {
  const std::string batch = kModels + "batch_small.toml";
  const fs::path first = out_dir("batch_first"), again = out_dir("batch_again");
  ASSERT_EQ(run_vorodec("batch " + batch + " --no-vtk --jobs 1 --out " + first.string()), 5);
  ASSERT_EQ(run_vorodec("batch " + batch + " --no-vtk --jobs 1 --out " + again.string()), 5);
  const std::string kept_log = slurp(again / "small_seed=11" / "log.txt");
  const auto rows_before = lines_of(again / "results.csv");
  // small_seed=12 was stopped at step 2000 (as a signal would), step_limit_seed=12 never ran.
  fs::remove(again / "small_seed=12" / "case_outcome.txt");
  fs::remove(again / "small_seed=12" / "summary.json");
  fs::remove_all(again / "step_limit_seed=12");
  const std::string command = slurp(again / "small_seed=12" / "case_command.txt");
  std::vector<std::string> args;
  std::istringstream lines(command);
  for (std::string a; std::getline(lines, a);)
    if (a.rfind("model files", 0) != 0) args.push_back("'" + a + "'");  // the command's lines
  std::string stop;
  for (std::size_t k = 1; k < args.size(); ++k) stop += " " + args[k];
  ASSERT_EQ(run_vorodec(stop + " --stop-at-step 2000"), kStopped);
  ASSERT_EQ(run_vorodec("batch " + batch + " --no-vtk --jobs 1 --out " + again.string()), 5);
  EXPECT_EQ(slurp(again / "small_seed=11" / "log.txt"), kept_log) << "a finished case ran again";
  const auto rows_first = lines_of(first / "results.csv"),
             rows_again = lines_of(again / "results.csv");
  ASSERT_EQ(rows_first.size(), rows_again.size());
  // The same results; the wall time (last column) is the run's own.
  for (std::size_t r = 0; r < rows_first.size(); ++r)
    EXPECT_EQ(rows_first[r].substr(0, rows_first[r].rfind(',')),
              rows_again[r].substr(0, rows_again[r].rfind(',')));
  for (const std::size_t kept : {1, 3})  // small_seed=11, step_limit_seed=11: the same rows
    EXPECT_EQ(rows_before[kept], rows_again[kept]);
  for (const char* c : {"small_seed=12", "step_limit_seed=12"})
    EXPECT_EQ(slurp(first / c / "history.csv"), slurp(again / c / "history.csv")) << c;
}

namespace {

// The state a resumed run saves again before its first step is the state it loaded: save and
// load visit the same fields (a field saved but not loaded, or loaded into the wrong place,
// shows here even where the run's outputs would not).
void expect_state_round_trips(const std::string& name, const std::string& model,
                              const std::string& extra) {
  const fs::path out = out_dir(name);
  ASSERT_EQ(run_vorodec("run " + model + " --threads 1 --no-vtk --stop-at-step 1000 --out " +
                        out.string() + extra),
            kStopped);
  const std::string first = vorodec::checkpoint::read_checkpoint(out / "checkpoint.vck").state;
  ASSERT_EQ(run_vorodec("resume " + out.string() + " --threads 2 --stop-at-step 1"), kStopped);
  const auto again = vorodec::checkpoint::read_checkpoint(out / "checkpoint.vck");
  EXPECT_EQ(again.header.step, 1000);
  EXPECT_TRUE(again.state == first) << "the state saved after loading differs from the one loaded";
}

}  // namespace

TEST(CheckpointState, LoadedAndSavedAgainIsTheSameBytesForRigidBlocks) {
  EXPECT_NO_FATAL_FAILURE(
      expect_state_round_trips("round_trip_rigid", kModels + "cyclic_small.toml", ""));
}

TEST(CheckpointState, LoadedAndSavedAgainIsTheSameBytesForZonedGrains) {
  EXPECT_NO_FATAL_FAILURE(
      expect_state_round_trips("round_trip_zoned", kModels + "grains_small.toml",
                               " --set blocks.deformable=true --set blocks.zone_size=1e-3"
                               " --set 'mineral[0].E=60e9' --set 'mineral[0].nu=0.25'"
                               " --set 'mineral[1].E=90e9' --set 'mineral[1].nu=0.1'"));
}

TEST(SignalledRun, StopsWithACheckpointOnSigtermAndResumesToTheUninterruptedResult) {
  const fs::path straight = out_dir("term_straight"), stopped = out_dir("term_stopped");
  ASSERT_EQ(run_vorodec("run " + marble_args(straight)), 0);
  const pid_t pid = start_vorodec("run " + marble_args(stopped));
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  // Signalled once it steps (its history has rows).
  while (lines_of(stopped / "history.csv").size() < 3 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), kStopped) << "the run ended before the signal";
  EXPECT_FALSE(fs::exists(stopped / "summary.json"));
  EXPECT_EQ(run_vorodec("resume " + stopped.string() + " --threads 2"), 0);
  expect_same_files(straight, stopped);
}

TEST(Progress, StagePercentagesNeverGoBack) {
  const Outcome o = run_capture("run " + kModels + "cyclic_small.toml --threads 1 --no-vtk --out " +
                                out_dir("progress").string());
  ASSERT_EQ(o.code, 0) << o.output;
  std::istringstream lines(o.output);
  std::string stage;
  double last = -1;
  int shown = 0;
  for (std::string line; std::getline(lines, line);) {
    const auto at = line.find("% of the stage");
    if (line.rfind("progress: stage ", 0) != 0 || at == std::string::npos) continue;
    const std::string this_stage = line.substr(16, line.find("  step") - 16);
    const double percent = std::stod(line.substr(line.rfind(' ', at - 1) + 1));
    if (this_stage != stage) last = -1;
    EXPECT_GE(percent, last) << line;
    stage = this_stage;
    last = percent;
    ++shown;
  }
  EXPECT_GT(shown, 3) << o.output;
}

TEST(Resume, DeformableRunStoppedAtItsStepLimitMatchesTheUninterruptedRun) {
  // The resumed run samples its end before any step: the zoned corners' shapes must come back.
  EXPECT_NO_FATAL_FAILURE(expect_resume_matches(
      "deformable_limit", kModels + "deformable_small.toml", {2000}, " --max-steps 2000"));
}

TEST(Resume, CreepRunStoppedInTheRampAndInACreepStageMatchesTheUninterruptedRun) {
  // creep_burgers_small: the ramp ends near step 12000, the first creep stage near 17000.
  EXPECT_NO_FATAL_FAILURE(expect_resume_matches("creep", kModels + "creep_burgers_small.toml",
                                                {6000, 14000, 19000}, " --no-vtk"));
}

TEST(CheckpointState, LoadedAndSavedAgainIsTheSameBytesInACreepStage) {
  // A steep, short ramp, so that step 1000 lies in the first creep stage.
  EXPECT_NO_FATAL_FAILURE(expect_state_round_trips(
      "round_trip_creep", kModels + "creep_burgers_small.toml",
      " --set 'stage[0].stress_rate=2e10' --set 'stage[0].end_axial_stress=6e6'"));
}
