// The run loop: a driver advances, observers sample, checkpoints are taken between steps.
#include "vorodec/run/run.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <sstream>

#include "progress.hpp"
#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/checkpoint/checkpoint_file.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/outputs/ae_output.hpp"
#include "vorodec/outputs/damage_output.hpp"
#include "vorodec/outputs/observers.hpp"
#include "vorodec/outputs/results.hpp"

namespace vorodec::run {

namespace fs = std::filesystem;

namespace {

// The signal that asks the running run to stop, or kStopRequested (request_stop); 0: none.
std::atomic<int> stop_signal{0};
constexpr int kStopRequested = -1;

extern "C" void on_stop_signal(int sig) {
  stop_signal.store(sig);
}

using Clock = std::chrono::steady_clock;

std::vector<std::string> flatten(const std::vector<io::Override>& overrides) {
  std::vector<std::string> out;
  for (const io::Override& o : overrides) out.insert(out.end(), {o.key, o.value, o.origin});
  return out;
}

std::uint32_t hash_of(const io::ModelConfig& cfg, const std::vector<io::Override>& overrides) {
  return checkpoint::model_hash(cfg.sources, flatten(overrides));
}

// Everything one run holds, fresh or resumed.
struct Run {
  const io::ModelConfig& cfg;
  const geometry::Tessellation& specimen;
  RunOptions options;
  checkpoint::Header header;  // of the checkpoints this run writes
  PreparedModel prepared;
  loading::SpecimenBoundary boundary;
  DamageOutput damage;
  measure::AeSettings ae;
  Curve curve;
  std::unique_ptr<Driver> driver;
  Observers observers;
  Progress progress;
  Clock::time_point wall0 = Clock::now(), last_checkpoint = wall0;
  double wall_before = 0;  // s, of the run's earlier parts (before a resume)
  long checkpoint_step = 0;
  int checkpoints = 0;  // written by this process, their wall time (s) and the last one's size
  double checkpoint_seconds = 0;
  std::size_t checkpoint_bytes = 0;

  Run(const io::ModelConfig& c, const geometry::Tessellation& t, const RunOptions& o)
      : cfg(c),
        specimen(t),
        options(o),
        prepared(prepare_model(c, t)),
        boundary(*prepared.model),
        damage(*prepared.model, c.output.damage_grid_cell),
        ae(ae_settings(c, damage.mean_block_size(), prepared.model->thickness)),
        driver(make_driver({c, *prepared.model, *prepared.solver, boundary, t,
                            o.max_steps > 0 ? o.max_steps : c.max_steps, o.max_steps > 0})),
        progress(o.progress, o.on_progress) {}

  double wall_seconds() const {
    return wall_before + std::chrono::duration<double>(Clock::now() - wall0).count();
  }

  void write_checkpoint() {
    const auto start = Clock::now();
    observers.flush();
    header.step = prepared.solver->steps();
    header.time = prepared.solver->time();
    header.wall_seconds = wall_seconds();
    checkpoint_bytes = checkpoint::write_checkpoint(options.out / kCheckpointFile, header,
                                                    [&](checkpoint::OutArchive& ar) {
                                                      model::save_state(ar, *prepared.model);
                                                      prepared.solver->save(ar);
                                                      driver->save(ar);
                                                      observers.save(ar);
                                                    });
    ++checkpoints;
    checkpoint_seconds += std::chrono::duration<double>(Clock::now() - start).count();
    last_checkpoint = Clock::now();
    checkpoint_step = prepared.solver->steps();
  }

  // Whether to write a checkpoint now, and whether to stop after it.
  std::pair<bool, bool> checkpoint_due() const {
    const long steps = prepared.solver->steps();
    const bool stop =
        stop_signal.load() != 0 || (options.stop_at_step > 0 && steps >= options.stop_at_step);
    const auto& o = cfg.output;
    const bool periodic =
        (o.checkpoint_steps > 0 && steps >= checkpoint_step + o.checkpoint_steps) ||
        (o.checkpoint_wall_time > 0 &&
         std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >=
             o.checkpoint_wall_time);
    return {stop || periodic, stop};
  }

  // What the checkpoints cost, on stderr (not in summary.json: a resumed run writes others).
  void report_checkpoints() const {
    if (checkpoints > 0)
      fmt::print(stderr, "checkpoints: {} written in {:.3f} s, {:.1f} MB each\n", checkpoints,
                 checkpoint_seconds, static_cast<double>(checkpoint_bytes) / 1e6);
  }

  RunSummary execute() {
    // From here a signal stops the run at its next step with a checkpoint; before, it ends it.
    stop_on_signals();
    while (!driver->finished()) {
      if (driver->resumable()) {
        const auto [write, stop] = checkpoint_due();
        if (write) write_checkpoint();
        if (stop) return stopped();
      }
      driver->advance(observers);
      observers.after_advance(driver->view());
      if (progress.due()) progress.show(driver->progress());
    }
    progress.finish();
    report_checkpoints();
    observers.flush();
    RunSummary s = write_results(cfg, *driver, curve, ae, wall_seconds(), options.out);
    std::error_code ec;
    fs::remove(options.out / kCheckpointFile, ec);  // a finished run has nothing to resume
    return s;
  }

  RunSummary stopped() {
    progress.finish();
    report_checkpoints();
    RunSummary s;
    s.exit_code = kStoppedForResume;
    const int sig = stop_signal_received();
    s.status = fmt::format("stopped {} at step {}, checkpoint written",
                           sig ? fmt::format("by signal {}", sig) : std::string("as asked"),
                           prepared.solver->steps());
    s.steps = prepared.solver->steps();
    s.blocks = prepared.model->blocks.size();
    s.wall_seconds = wall_seconds();
    return s;
  }
};

}  // namespace

void stop_on_signals() {
  stop_signal.store(0);
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sa.sa_flags = SA_RESETHAND;  // a second signal ends the run at once
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

void request_stop() {
  stop_signal.store(kStopRequested);
}

int stop_signal_received() {
  const int sig = stop_signal.load();
  return sig == kStopRequested ? 0 : sig;
}

// What a kill during a whole-file write left: the temporary names (io/atomic_file.hpp).
void remove_partial_files(const fs::path& out) {
  std::error_code ec;
  for (const fs::path& dir : {out, out / "vtk"})
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".tmp") fs::remove(e.path(), ec);
}

RunSummary run_model(const io::ModelConfig& cfg, const geometry::Tessellation& specimen,
                     const RunOptions& options, const std::vector<io::Override>& overrides) {
  std::error_code ec;
  fs::remove(options.out / kCheckpointFile, ec);  // another run's: never resume it by mistake
  remove_partial_files(options.out);
  Run run(cfg, specimen, options);
  run.header = {VORODEC_VERSION,    fs::absolute(cfg.file).string(),
                flatten(overrides), hash_of(cfg, overrides),
                options.max_steps,  options.write_vtk};
  run.observers = make_observers(run.driver->view(), run.damage, run.ae, options.out,
                                 options.write_vtk, run.curve, nullptr);
  return run.execute();
}

RunSummary resume_run(const fs::path& dir, long stop_at_step, bool progress,
                      std::function<void(const ProgressReport&)> on_progress) {
  const checkpoint::Contents contents = checkpoint::read_checkpoint(dir / kCheckpointFile);
  const checkpoint::Header& h = contents.header;
  std::vector<io::Override> overrides;
  for (std::size_t i = 0; i + 2 < h.overrides.size(); i += 3)
    overrides.push_back({h.overrides[i], h.overrides[i + 1], h.overrides[i + 2]});
  const io::ModelConfig cfg = run::read_model_file(h.model_file, overrides);
  if (hash_of(cfg, overrides) != h.model_hash)
    throw checkpoint::CheckpointError(fmt::format(
        "{}: the model file {} (or a file it reads) changed since the checkpoint was written: "
        "resume only the run it was written for, or start it again",
        (dir / kCheckpointFile).string(), h.model_file));
  const geometry::Tessellation specimen = make_specimen(cfg);
  RunOptions options{dir, h.max_steps, h.write_vtk, progress, stop_at_step, std::move(on_progress)};
  Run run(cfg, specimen, options);
  run.header = h;
  run.wall_before = h.wall_seconds;
  remove_partial_files(dir);
  for (const char* end : {"summary.json", "cycles.csv"}) {  // a later end than the checkpoint's
    std::error_code ec;
    fs::remove(dir / end, ec);
  }
  try {
    std::istringstream state(contents.state);
    checkpoint::InArchive ar(state);
    model::load_state(ar, *run.prepared.model);
    run.prepared.solver->load(ar);
    run.driver->load(ar);
    run.observers =
        make_observers(run.driver->view(), run.damage, run.ae, dir, h.write_vtk, run.curve, &ar);
  } catch (const std::exception& e) {  // a state that does not fit the model, or spoilt outputs
    throw checkpoint::CheckpointError(
        fmt::format("{}: cannot continue from it: {}", (dir / kCheckpointFile).string(), e.what()));
  }
  run.checkpoint_step = run.prepared.solver->steps();
  return run.execute();
}

}  // namespace vorodec::run
