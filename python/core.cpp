// vorodec._core: the library the `vorodec` command runs, called inside the Python process.
// vorodec/__init__.py wraps it for users (docs/python.md).
#include <fmt/format.h>
#include <omp.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <unistd.h>

#include <csignal>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "vorodec/checkpoint/checkpoint_file.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/io/specimen_file.hpp"
#include "vorodec/laws/reference.hpp"
#include "vorodec/run/run.hpp"
#include "vorodec/workflows/batch.hpp"
#include "vorodec/workflows/batch_file.hpp"
#include "vorodec/workflows/calibrate.hpp"
#include "vorodec/workflows/calibration_file.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace vorodec;

namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;  // key, TOML value text

// `set` as overrides, named "set" in messages as `--set` is on the command line.
std::vector<io::Override> overrides_of(const Overrides& set) {
  std::vector<io::Override> overrides;
  for (const auto& [key, value] : set) overrides.push_back({key, value, "set"});
  return overrides;
}

io::ModelConfig read_model(const fs::path& file, const Overrides& set) {
  return run::read_model_file(file, overrides_of(set));
}

// A results folder that can be written; otherwise bad input, as the command's --out.
void prepare_out(const fs::path& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || access(out.c_str(), W_OK) != 0)
    throw io::ModelFileError(
        fmt::format("out '{}': output folder cannot be created or written", out.string()));
}

// OpenMP threads of the calling thread for one call (0: unchanged), then as they were.
class ThreadCount {
 public:
  explicit ThreadCount(int threads) : before_(omp_get_max_threads()) {
    if (threads > 0) omp_set_num_threads(threads);
  }
  ~ThreadCount() { omp_set_num_threads(before_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int before_;
};

// Python's own SIGINT and SIGTERM handlers, given back when a run (which installs the stop-with-a-
// checkpoint handlers) returns.
class SignalHandlers {
 public:
  SignalHandlers() {
    sigaction(SIGINT, nullptr, &int_);
    sigaction(SIGTERM, nullptr, &term_);
  }
  ~SignalHandlers() {
    sigaction(SIGINT, &int_, nullptr);
    sigaction(SIGTERM, &term_, nullptr);
  }
  SignalHandlers(const SignalHandlers&) = delete;
  SignalHandlers& operator=(const SignalHandlers&) = delete;

 private:
  struct sigaction int_ = {};
  struct sigaction term_ = {};
};

py::dict report_dict(const run::ProgressReport& r) {
  py::dict d;
  d["stage"] = r.stage;
  d["stages"] = r.stages;
  d["stage_name"] = r.stage_name;
  d["steps"] = r.steps;
  d["stress"] = r.stress;
  d["fraction"] = r.fraction;
  d["waiting"] = r.waiting;
  d["clock"] = r.clock;
  return d;
}

// The progress callback as the run loop calls it (GIL released): with the GIL taken; an exception
// it raises stops the run with a checkpoint and is raised again once the run has returned.
struct ProgressBridge {
  py::object callback;
  std::exception_ptr raised;

  std::function<void(const run::ProgressReport&)> function() {
    if (callback.is_none()) return {};
    return [this](const run::ProgressReport& r) {
      py::gil_scoped_acquire gil;
      if (raised) return;
      try {
        callback(report_dict(r));
      } catch (py::error_already_set&) {
        raised = std::current_exception();
        run::request_stop();
      }
    };
  }
};

py::dict outcome_dict(const run::RunSummary& s, const fs::path& out) {
  py::dict d;
  d["exit_code"] = s.exit_code;
  d["status"] = s.status;
  d["steps"] = s.steps;
  d["wall_seconds"] = s.wall_seconds;
  d["signal"] = run::stop_signal_received();
  d["out"] = out;
  return d;
}

// check and build: the model read, its specimen made.
py::dict specimen(const fs::path& file, const Overrides& set, const fs::path& out) {
  std::string report, load_path;
  std::vector<std::string> warnings;
  std::size_t blocks = 0;
  {
    py::gil_scoped_release release;
    const io::ModelConfig cfg = read_model(file, set);
    const geometry::Tessellation t = run::make_specimen(cfg);
    report = run::specimen_report(cfg, t);
    warnings = t.report.warnings;
    blocks = t.blocks.size();
    load_path = cfg.load_path.stages.empty()
                    ? fmt::format("a [{}] test", run::driver_name(cfg))
                    : fmt::format("{} stages", cfg.load_path.stages.size());
    if (!out.empty()) {
      prepare_out(out);
      io::write_specimen(out / "specimen.vsp", t, run::describe_contacts(cfg, t));
    }
  }
  py::dict d;
  d["blocks"] = blocks;
  d["report"] = report;
  d["warnings"] = warnings;
  d["load_path"] = load_path;
  if (!out.empty()) d["specimen_file"] = out / "specimen.vsp";
  return d;
}

py::dict run_model(const fs::path& file, const Overrides& set, const fs::path& out, int threads,
                   long max_steps, bool vtk, long stop_at_step, bool progress,
                   py::object callback) {
  ProgressBridge bridge{std::move(callback), nullptr};
  run::RunSummary s;
  {
    py::gil_scoped_release release;
    const ThreadCount thread_count(threads);
    const io::ModelConfig cfg = read_model(file, set);
    const geometry::Tessellation t = run::make_specimen(cfg);
    prepare_out(out);
    const SignalHandlers python_handlers;
    const run::RunOptions options{out, max_steps, vtk, progress, stop_at_step, bridge.function()};
    s = run::run_model(cfg, t, options, overrides_of(set));
  }
  if (bridge.raised) std::rethrow_exception(bridge.raised);
  return outcome_dict(s, out);
}

py::dict resume(const fs::path& dir, int threads, long stop_at_step, bool progress,
                py::object callback) {
  ProgressBridge bridge{std::move(callback), nullptr};
  run::RunSummary s;
  {
    py::gil_scoped_release release;
    const ThreadCount thread_count(threads);
    const SignalHandlers python_handlers;
    s = run::resume_run(dir, stop_at_step, progress, bridge.function());
  }
  if (bridge.raised) std::rethrow_exception(bridge.raised);
  return outcome_dict(s, dir);
}

// The exit code and the results folder.
std::pair<int, fs::path> batch(const fs::path& file, const fs::path& out, int jobs, long max_steps,
                               bool vtk) {
  py::gil_scoped_release release;
  // Bad input raised with its message here; run_batch would print it and return 2.
  const workflows::BatchPlan plan = workflows::read_batch_file(file);
  for (const workflows::BatchCase& c : plan.cases) run::read_model_file(c.model, c.overrides);
  const fs::path folder = out.empty() ? plan.output : out;
  return {workflows::run_batch({file, folder, jobs, max_steps, vtk, VORODEC_CLI}), folder};
}

std::pair<int, fs::path> calibrate(const fs::path& file, const fs::path& out, int jobs,
                                   bool check) {
  py::gil_scoped_release release;
  const fs::path folder = out.empty() ? workflows::read_calibration_file(file).output : out;
  return {workflows::calibrate({file, folder, jobs, check, VORODEC_CLI}), folder};
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "vorodec's native part; use the vorodec package (docs/python.md)";
  m.attr("__version__") = VORODEC_VERSION;
  m.attr("cli") = fs::path(VORODEC_CLI);
  static py::exception<io::ModelFileError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::ModelFileError& e) {
      input_error(e.what());
    } catch (const checkpoint::CheckpointError& e) {
      input_error(e.what());
    }
  });
  m.def("specimen", &specimen, py::arg("file"), py::arg("set"), py::arg("out"));
  m.def("run", &run_model, py::arg("file"), py::arg("set"), py::arg("out"), py::arg("threads"),
        py::arg("max_steps"), py::arg("vtk"), py::arg("stop_at_step"), py::arg("progress"),
        py::arg("callback"));
  m.def("resume", &resume, py::arg("dir"), py::arg("threads"), py::arg("stop_at_step"),
        py::arg("progress"), py::arg("callback"));
  m.def("batch", &batch, py::arg("file"), py::arg("out"), py::arg("jobs"), py::arg("max_steps"),
        py::arg("vtk"));
  m.def("calibrate", &calibrate, py::arg("file"), py::arg("out"), py::arg("jobs"),
        py::arg("check"));
  m.def("laws", &laws::law_reference);
}
