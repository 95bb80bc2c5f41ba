#include "vorodec/app/batch.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

#include "cluster.hpp"
#include "vorodec/app/simulation.hpp"
#include "vorodec/checkpoint/checkpoint_file.hpp"
#include "vorodec/io/atomic_file.hpp"
#include "vorodec/io/batch_file.hpp"

extern char** environ;

namespace vorodec::app {

namespace fs = std::filesystem;

namespace {

constexpr int bad_input = 2, some_case_failed = 5;

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + '"';
}

// One field of the summary.json vorodec run writes, as written ("" if absent).
std::string json_field(const std::string& text, const std::string& key) {
  const std::string tag = "\"" + key + "\":";
  auto pos = text.find(tag);
  if (pos == std::string::npos) return {};
  pos = text.find_first_not_of(' ', pos + tag.size());
  if (pos == std::string::npos) return {};
  if (text[pos] == '"') {
    const auto end = text.find("\",\n", pos + 1);
    return end == std::string::npos ? std::string() : text.substr(pos + 1, end - pos - 1);
  }
  const auto end = text.find_first_of(",\n}", pos);
  return text.substr(pos, end - pos);
}

struct Outcome {
  int exit_code = 0;
  double wall_seconds = 0;
};

// The command line of one case: a plain `vorodec run`, so a case can be rerun by hand.
std::vector<std::string> case_command(const io::BatchCase& c, const fs::path& dir,
                                      const BatchOptions& options) {
  std::vector<std::string> args{"vorodec",   "run", c.model.string(), "--out", dir.string(),
                                "--threads", "1"};
  if (options.max_steps > 0) {
    args.push_back("--max-steps");
    args.push_back(std::to_string(options.max_steps));
  }
  if (!options.write_vtk) args.push_back("--no-vtk");
  for (const io::Override& o : c.overrides) {
    args.push_back("--set");
    args.push_back(o.key + "=" + o.value);
  }
  return args;
}

std::string joined(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) s += a + '\n';
  return s;
}

// What a case is: its command line and what its model files hold (an edited model is another case).
std::string case_identity(const io::BatchCase& c, const std::vector<std::string>& command) {
  std::vector<std::string> overrides;
  for (const io::Override& o : c.overrides) overrides.insert(overrides.end(), {o.key, o.value});
  const io::ModelConfig cfg = io::read_model_file(c.model, c.overrides);
  return joined(command) +
         fmt::format("model files crc32 {:08x}\n", checkpoint::model_hash(cfg.sources, overrides));
}

// In a case's folder: its identity (case_identity) when it was started, and once it ended for good
// (any exit but a stop for resume or a signal), its exit code and wall time.
constexpr const char* kCaseCommand = "case_command.txt";
constexpr const char* kCaseOutcome = "case_outcome.txt";

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool ended_for_good(int exit_code) {
  return exit_code != kStoppedForResume && exit_code < 128;
}

// The outcome of the case in `dir` if it ran to its end with this very command.
std::optional<Outcome> finished_before(const fs::path& dir, const std::string& command) {
  if (!fs::exists(dir / kCaseOutcome) || read_text(dir / kCaseCommand) != command) return {};
  std::istringstream in(read_text(dir / kCaseOutcome));
  Outcome o;
  if (!(in >> o.exit_code >> o.wall_seconds) || !ended_for_good(o.exit_code)) return {};
  return o;
}

// s, the wall time a stopped case's checkpoint records (0 if it cannot be read: the resume
// will say why).
double earlier_wall_seconds(const fs::path& dir) {
  try {
    return checkpoint::read_checkpoint(dir / kCheckpointFile).header.wall_seconds;
  } catch (const checkpoint::CheckpointError&) {
    return 0.0;
  }
}

pid_t spawn_case(const std::vector<std::string>& args, const fs::path& dir, bool append_log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string log = (dir / "log.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | (append_log ? O_APPEND : O_TRUNC), 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  const int err = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) throw std::runtime_error(fmt::format("cannot start a case: {}", strerror(err)));
  return pid;
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 1;  // as a shell reports a signal
}

// Runs the cases `mine` (indices into plan.cases), `jobs` at a time.
std::map<std::size_t, Outcome> run_cases(const io::BatchPlan& plan,
                                         const std::vector<std::size_t>& mine, const fs::path& out,
                                         const BatchOptions& options, int jobs,
                                         const std::string& who) {
  using clock = std::chrono::steady_clock;
  std::map<std::size_t, Outcome> done;
  struct Running {
    std::size_t i;
    clock::time_point start;
    double earlier_seconds;  // of the case's parts before it was resumed
  };
  std::map<pid_t, Running> running;
  std::size_t next = 0;
  while (next < mine.size() || !running.empty()) {
    while (next < mine.size() && running.size() < static_cast<std::size_t>(jobs)) {
      const std::size_t i = mine[next++];
      const io::BatchCase& c = plan.cases[i];
      const fs::path dir = out / c.name;
      fs::create_directories(dir);
      const std::vector<std::string> command = case_command(c, dir, options);
      const std::string identity = case_identity(c, command);
      // A batch run again on its folder continues: finished cases are kept as they are,
      // stopped ones resume from their checkpoints, the others run.
      if (const std::optional<Outcome> o = finished_before(dir, identity)) {
        done[i] = *o;
        fmt::print("{}case {}/{} {}: kept, it finished before (exit {})\n", who, i + 1,
                   plan.cases.size(), c.name, o->exit_code);
        continue;
      }
      const bool resume =
          fs::exists(dir / kCheckpointFile) && read_text(dir / kCaseCommand) == identity;
      fs::remove(dir / kCaseOutcome);
      if (!resume) fs::remove(dir / "summary.json");  // never report a previous batch's result
      io::write_file_atomically(dir / kCaseCommand, identity);
      const std::vector<std::string> args =
          resume ? std::vector<std::string>{"vorodec", "resume", dir.string(), "--threads", "1"}
                 : command;
      // A resumed case's wall time counts its earlier parts, as its summary does.
      const double earlier = resume ? earlier_wall_seconds(dir) : 0.0;
      running[spawn_case(args, dir, resume)] = {i, clock::now(), earlier};
    }
    if (running.empty()) continue;  // every remaining case had finished before
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) throw std::runtime_error("lost track of the running cases");
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running r = it->second;
    running.erase(it);
    const std::size_t i = r.i;
    Outcome o{exit_code_of(status),
              r.earlier_seconds + std::chrono::duration<double>(clock::now() - r.start).count()};
    done[i] = o;
    const fs::path dir = out / plan.cases[i].name;
    if (ended_for_good(o.exit_code))
      io::write_file_atomically(dir / kCaseOutcome,
                                fmt::format("{} {:.17g}\n", o.exit_code, o.wall_seconds));
    fmt::print("{}case {}/{} {}: exit {} after {:.1f} s\n", who, i + 1, plan.cases.size(),
               plan.cases[i].name, o.exit_code, o.wall_seconds);
    std::fflush(stdout);
  }
  return done;
}

std::string header(const io::BatchPlan& plan) {
  std::string h = "case,model";
  for (const std::string& key : plan.columns) h.append(",").append(csv_field(key));
  return h +
         ",exit_code,status,peak_stress_Pa,youngs_modulus_Pa,poisson_ratio,steps,cracks_tensile,"
         "cracks_shear,wall_time_s\n";
}

std::string row(const io::BatchPlan& plan, std::size_t i, const Outcome& o, const fs::path& out) {
  const io::BatchCase& c = plan.cases[i];
  const std::string summary = read_text(out / c.name / "summary.json");
  const std::string status = summary.empty() ? fmt::format("no summary, see {}/log.txt", c.name)
                                             : json_field(summary, "status");
  // Appends only: GCC 12 warns (-Wrestrict, falsely) about "," + std::string here.
  std::string r = csv_field(c.name);
  r.append(",").append(csv_field(c.model.string()));
  for (const std::string& key : plan.columns)
    r.append(",").append(csv_field(io::override_value(c, key)));
  r += fmt::format(",{},{}", o.exit_code, csv_field(status));
  for (const char* key : {"peak_stress_Pa", "youngs_modulus_Pa", "poisson_ratio", "steps"})
    r.append(",").append(json_field(summary, key));
  for (const char* key : {"tensile", "shear"}) r.append(",").append(json_field(summary, key));
  return r + fmt::format(",{:.3f}\n", o.wall_seconds);
}

}  // namespace

int run_batch(const BatchOptions& options) {
  Cluster cluster;
  const bool lead = cluster.rank() == 0;
  if (cluster.launched_without_mpi()) {
    fmt::print(stderr,
               "error: started as several MPI ranks, but this vorodec was built without MPI "
               "(cmake -DVORODEC_MPI=ON with libopenmpi-dev installed)\n");
    return bad_input;
  }
  io::BatchPlan plan;
  try {
    plan = io::read_batch_file(options.batch_file);
    for (const io::BatchCase& c : plan.cases) io::read_model_file(c.model, c.overrides);
  } catch (const io::ModelFileError& e) {
    if (lead) fmt::print(stderr, "error: {}\n", e.what());
    return bad_input;  // every rank read the same files and stops here alike
  }
  const fs::path out = options.out.empty() ? plan.output : options.out;
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) {
    fmt::print(stderr, "error: results folder '{}' cannot be created\n", out.string());
    cluster.abort(bad_input);
  }
  int jobs = options.jobs;
  if (jobs <= 0)
    jobs =
        cluster.size() > 1 ? 1 : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::vector<std::size_t> mine;
  for (std::size_t i = static_cast<std::size_t>(cluster.rank()); i < plan.cases.size();
       i += static_cast<std::size_t>(cluster.size()))
    mine.push_back(i);
  const std::string who = cluster.size() > 1 ? fmt::format("rank {}: ", cluster.rank()) : "";
  if (lead)
    fmt::print("{}: {} cases, {} process(es) x {} at a time, results in {}/\n",
               options.batch_file.string(), plan.cases.size(), cluster.size(), jobs, out.string());

  // Rows travel as "index<TAB>exit code<TAB>row" lines, so rank 0 can put them in case order.
  std::string rows;
  try {
    for (const auto& [i, o] : run_cases(plan, mine, out, options, jobs, who))
      rows += fmt::format("{}\t{}\t{}", i, o.exit_code, row(plan, i, o, out));
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}error: {}\n", who, e.what());
    cluster.abort(1);
  }
  const std::vector<std::string> gathered = cluster.gather(rows);
  // Only rank 0 reports failed cases: mpirun kills the job at a rank's non-zero exit, perhaps
  // before rank 0 has written the table.
  if (!lead) return 0;

  std::map<std::size_t, std::string> ordered;
  bool all_ok = true;
  for (const std::string& text : gathered) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
      const auto tab1 = line.find('\t'), tab2 = line.find('\t', tab1 + 1);
      ordered[std::stoul(line.substr(0, tab1))] = line.substr(tab2 + 1);
      all_ok &= line.substr(tab1 + 1, tab2 - tab1 - 1) == "0";
    }
  }
  std::string table = header(plan);
  for (const auto& [i, r] : ordered) table += r + '\n';
  io::write_file_atomically(out / "results.csv", table);
  fs::copy_file(options.batch_file, out / "batch.toml", fs::copy_options::overwrite_existing, ec);
  fmt::print("results.csv: {} rows in {}/\n", ordered.size(), out.string());
  return all_ok ? 0 : some_case_failed;
}

}  // namespace vorodec::app
