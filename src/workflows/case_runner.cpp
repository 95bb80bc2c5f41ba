#include "case_runner.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "vorodec/checkpoint/checkpoint_file.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/io/atomic_file.hpp"
#include "vorodec/run/run.hpp"
#include "vorodec/workflows/calibration_file.hpp"

extern char** environ;

namespace vorodec::workflows {

namespace fs = std::filesystem;

namespace {

// The command line of one case: a plain `vorodec run`, so a case can be rerun by hand.
std::vector<std::string> case_command(const BatchCase& c, const fs::path& dir,
                                      const CaseOptions& options) {
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
// The command names the model and the folder by absolute paths, so that a rerun spelling them
// otherwise (relative or absolute, through "./") is the same case.
std::string case_identity(const BatchCase& c, const fs::path& dir, const CaseOptions& options) {
  BatchCase named = c;
  named.model = fs::absolute(c.model).lexically_normal();
  std::vector<std::string> overrides;
  for (const io::Override& o : c.overrides) overrides.insert(overrides.end(), {o.key, o.value});
  const io::ModelConfig cfg = run::read_model_file(c.model, c.overrides);
  return joined(case_command(named, fs::absolute(dir).lexically_normal(), options)) +
         fmt::format("model files crc32 {:08x}\n", checkpoint::model_hash(cfg.sources, overrides));
}

// In a case's folder: its identity (case_identity) when it was started, and once it ended for good
// (any exit but a stop for resume or a signal), its exit code and wall time.
constexpr const char* kCaseCommand = "case_command.txt";
constexpr const char* kCaseOutcome = "case_outcome.txt";

bool ended_for_good(int exit_code) {
  return exit_code != run::kStoppedForResume && exit_code < 128;
}

// The outcome of the case in `dir` if it ran to its end with this very command.
std::optional<CaseOutcome> finished_before(const fs::path& dir, const std::string& command) {
  if (!fs::exists(dir / kCaseOutcome) || read_text(dir / kCaseCommand) != command) return {};
  std::istringstream in(read_text(dir / kCaseOutcome));
  CaseOutcome o;
  if (!(in >> o.exit_code >> o.wall_seconds) || !ended_for_good(o.exit_code)) return {};
  o.kept = true;
  return o;
}

// s, the wall time a stopped case's checkpoint records (0 if it cannot be read: the resume
// will say why).
double earlier_wall_seconds(const fs::path& dir) {
  try {
    return checkpoint::read_checkpoint(dir / run::kCheckpointFile).header.wall_seconds;
  } catch (const checkpoint::CheckpointError&) {
    return 0.0;
  }
}

pid_t spawn_case(const fs::path& executable, const std::vector<std::string>& args,
                 const fs::path& dir, bool append_log) {
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
  const int err = posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) throw std::runtime_error(fmt::format("cannot start a case: {}", strerror(err)));
  return pid;
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 1;  // as a shell reports a signal
}

}  // namespace

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

io::Json read_summary(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return nullptr;
  io::Json summary = io::Json::parse(in, nullptr, false);  // no exception: discarded if malformed
  return summary.is_discarded() ? io::Json() : summary;
}

io::Json summary_value(const io::Json& summary, const std::string& name) {
  // Where summary.json keeps the nested numbers a batch or a calibration asks for by name.
  static const std::map<std::string, std::string> nested = {
      {"tensile", "/cracks/tensile"},
      {"shear", "/cracks/shear"},
      {"crack_initiation_stress_Pa", "/failure_stages/crack_initiation_stress_Pa"},
      {"accelerating_crack_growth_stress_Pa",
       "/failure_stages/accelerating_crack_growth_stress_Pa"},
      {"linear_youngs_modulus_Pa", "/implicit_start/linear_youngs_modulus_Pa"},
      {"failure_time_s", "/corrosion_stages/0/failure_time_s"}};
  if (!summary.is_object()) return nullptr;
  if (summary.contains(name)) return summary[name];
  const auto path = nested.find(name);
  std::string pointer_text = path != nested.end() ? path->second : "/" + name;
  if (path == nested.end()) std::replace(pointer_text.begin(), pointer_text.end(), '.', '/');
  try {
    const io::Json::json_pointer pointer(pointer_text);
    return summary.contains(pointer) ? summary[pointer] : io::Json();
  } catch (const io::Json::exception&) {  // a path through a list by a name: not there
    return nullptr;
  }
}

namespace {

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

// A history.csv column where another first reaches a value (from below, interpolated between the
// rows around it), or at the last row of a stage mark; NaN where the run never got there.
double history_value(const fs::path& file, const std::string& name, const HistoryPoint& at) {
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) return NAN;
  const std::vector<std::string> header = csv_fields(line);
  const auto column = [&](const std::string& c) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), c) - header.begin());
  };
  const std::size_t y = column(name), x = column(at.column);
  if (y == header.size() || x == header.size()) return NAN;
  double found = NAN, x0 = NAN, y0 = NAN;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != header.size()) continue;
    const double yi = std::strtod(f[y].c_str(), nullptr);
    if (!at.stage.empty()) {
      if (f[x] == at.stage) found = yi;
      continue;
    }
    const double xi = std::strtod(f[x].c_str(), nullptr);
    if (xi >= at.value) {
      if (std::isnan(x0) || xi == x0) return yi;
      return y0 + (yi - y0) * (at.value - x0) / (xi - x0);
    }
    x0 = xi;
    y0 = yi;
  }
  return found;
}

}  // namespace

double run_quantity(const fs::path& run_dir, const RunQuantity& q) {
  if (q.history) {
    const fs::path file = run_dir / "history.csv";
    const double at = history_value(file, q.name, q.at);
    if (q.from.column.empty()) return at;
    return at - history_value(file, q.name, q.from);
  }
  const io::Json v = summary_value(read_summary(run_dir / "summary.json"), q.name);
  return v.is_number() ? v.get<double>() : NAN;
}

std::map<std::size_t, CaseOutcome> run_cases(const std::vector<BatchCase>& cases,
                                             const std::vector<std::size_t>& mine,
                                             const fs::path& out, const CaseOptions& options,
                                             int jobs, const std::string& who) {
  using clock = std::chrono::steady_clock;
  std::map<std::size_t, CaseOutcome> done;
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
      const BatchCase& c = cases[i];
      const fs::path dir = out / c.name;
      fs::create_directories(dir);
      const std::vector<std::string> command = case_command(c, dir, options);
      const std::string identity = case_identity(c, dir, options);
      if (const std::optional<CaseOutcome> o = finished_before(dir, identity)) {
        done[i] = *o;
        fmt::print("{}case {}/{} {}: kept, it finished before (exit {})\n", who, i + 1,
                   cases.size(), c.name, o->exit_code);
        continue;
      }
      const bool resume =
          fs::exists(dir / run::kCheckpointFile) && read_text(dir / kCaseCommand) == identity;
      fs::remove(dir / kCaseOutcome);
      if (!resume) fs::remove(dir / "summary.json");  // never report a previous run's result
      io::write_file_atomically(dir / kCaseCommand, identity);
      const std::vector<std::string> args =
          resume ? std::vector<std::string>{"vorodec", "resume", dir.string(), "--threads", "1"}
                 : command;
      // A resumed case's wall time counts its earlier parts, as its summary does.
      const double earlier = resume ? earlier_wall_seconds(dir) : 0.0;
      running[spawn_case(options.executable, args, dir, resume)] = {i, clock::now(), earlier};
    }
    if (running.empty()) continue;  // every remaining case had finished before
    int status = 0;
    pid_t pid = -1;
    do {  // a signal the calling process handles (Python's SIGINT) interrupts the wait
      pid = waitpid(-1, &status, 0);
    } while (pid < 0 && errno == EINTR);
    if (pid < 0) throw std::runtime_error("lost track of the running cases");
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running r = it->second;
    running.erase(it);
    const std::size_t i = r.i;
    CaseOutcome o{
        exit_code_of(status),
        r.earlier_seconds + std::chrono::duration<double>(clock::now() - r.start).count()};
    done[i] = o;
    const fs::path dir = out / cases[i].name;
    if (ended_for_good(o.exit_code))
      io::write_file_atomically(dir / kCaseOutcome,
                                fmt::format("{} {:.17g}\n", o.exit_code, o.wall_seconds));
    fmt::print("{}case {}/{} {}: exit {} after {:.1f} s\n", who, i + 1, cases.size(), cases[i].name,
               o.exit_code, o.wall_seconds);
    std::fflush(stdout);
  }
  return done;
}

}  // namespace vorodec::workflows
