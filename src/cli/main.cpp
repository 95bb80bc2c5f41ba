// The vorodec command: run, resume, check and build model files, run batches, calibrate, and
// print the contact laws' key reference.
#include <fmt/format.h>
#include <omp.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>

#include "vorodec/checkpoint/checkpoint_file.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/io/specimen_file.hpp"
#include "vorodec/laws/reference.hpp"
#include "vorodec/run/run.hpp"
#include "vorodec/workflows/batch.hpp"
#include "vorodec/workflows/calibrate.hpp"

namespace fs = std::filesystem;
using namespace vorodec;

namespace {

constexpr int bad_input = 2;

// Creates (or checks) the results folder; an unwritable folder is bad input.
bool prepare_out(const fs::path& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  const fs::path probe = out / ".vorodec-write-test";
  if (!ec) {
    std::FILE* f = std::fopen(probe.string().c_str(), "w");
    if (f) {
      std::fclose(f);
      fs::remove(probe, ec);
      return true;
    }
  }
  fmt::print(stderr, "error: --out '{}': output folder cannot be created or written\n",
             out.string());
  return false;
}

// `--set key=value` options as overrides of the model file.
std::vector<io::Override> parse_sets(const std::vector<std::string>& sets) {
  std::vector<io::Override> out;
  for (const std::string& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw io::ModelFileError(fmt::format("--set '{}': write KEY=VALUE, e.g. seed=7", s));
    out.push_back({s.substr(0, eq), s.substr(eq + 1), "--set"});
  }
  return out;
}

void print_report(const geometry::Tessellation& t, const io::ModelConfig& cfg) {
  fmt::print("{}", run::specimen_report(cfg, t));
  for (const auto& w : t.report.warnings) fmt::print(stderr, "warning: specimen: {}\n", w);
}

void print_outcome(const std::string& what, const run::RunSummary& s, const fs::path& out) {
  if (s.exit_code == run::kStoppedForResume) {
    fmt::print("{}: {} after {:.1f} s; continue with `vorodec resume {}`\n", what, s.status,
               s.wall_seconds, out.string());
    return;
  }
  fmt::print(
      "{}: {} after {} steps in {:.1f} s; {} {:.2f} MPa,{} E {:.2f} GPa, nu {:.3f}; "
      "cracks {} tensile, {} shear\nresults in {}/ (history.csv, summary.json, cracks.csv, "
      "vtk/*.pvd)\n",
      what, s.status, s.steps, s.wall_seconds,
      s.peak_passed ? "peak stress" : "highest stress (no peak: it never fell 1 % below)",
      s.peak_stress / 1e6,
      s.tensile_strength > 0
          ? fmt::format(" tensile strength {:.2f} MPa,", s.tensile_strength / 1e6)
          : "",
      s.youngs_modulus / 1e9, s.poisson_ratio, s.cracks_tensile, s.cracks_shear, out.string());
}

// Every option of every command; CLI11 fills them.
struct Options {
  std::string model_path, out_dir, resume_dir;
  int threads = 0;
  long max_steps = 0, stop_at_step = 0;
  bool no_vtk = false;
  std::vector<std::string> sets;
  workflows::BatchOptions batch;
  workflows::CalibrateOptions calibrate;
};

struct Commands {
  CLI::App *run, *resume, *check, *build, *batch, *calibrate, *laws;
};

void add_set(CLI::App* sub, Options& o) {
  sub->add_option("--set", o.sets,
                  "override a model-file key, KEY=VALUE with a TOML value "
                  "(loading.confining_stress=5e6); repeatable")
      ->expected(1)
      ->take_all();
}

// run, resume, check, build: one model file.
void add_model_commands(CLI::App& cli, Options& o, Commands& c) {
  c.run = cli.add_subcommand("run", "run a model file to the end of its load path");
  c.run->add_option("model", o.model_path, "model file (.toml)")->required();
  c.run->add_option("--out", o.out_dir, "results folder (default: results/<model name>)");
  c.run->add_option("--threads", o.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::PositiveNumber);
  c.run->add_option("--max-steps", o.max_steps, "stop after this many steps (short runs)")
      ->check(CLI::PositiveNumber);
  c.run->add_flag("--no-vtk", o.no_vtk, "do not write the VTK series");
  c.run
      ->add_option("--stop-at-step", o.stop_at_step,
                   "write a checkpoint at this step and stop (exit 6), for `vorodec resume`")
      ->check(CLI::PositiveNumber);
  add_set(c.run, o);

  c.resume = cli.add_subcommand("resume", "continue a stopped run from its checkpoint");
  c.resume->add_option("dir", o.resume_dir, "results folder of the stopped run")->required();
  c.resume->add_option("--threads", o.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::PositiveNumber);
  c.resume->add_option("--stop-at-step", o.stop_at_step, "stop again at this step (exit 6)")
      ->check(CLI::PositiveNumber);

  c.check = cli.add_subcommand("check", "validate a model file and its specimen, run nothing");
  c.check->add_option("model", o.model_path, "model file (.toml)")->required();
  add_set(c.check, o);

  c.build = cli.add_subcommand("build", "build the specimen and save it for `specimen.file`");
  c.build->add_option("model", o.model_path, "model file (.toml)")->required();
  c.build->add_option("--out", o.out_dir,
                      "folder for specimen.vsp (default: results/<model name>)");
}

// batch, calibrate: many runs; laws: the laws' key reference.
void add_workflow_commands(CLI::App& cli, Options& o, Commands& c) {
  c.batch = cli.add_subcommand("batch", "run every case of a batch file (also under mpirun)");
  c.batch->add_option("batch_file", o.batch.batch_file, "batch file (.toml)")->required();
  c.batch->add_option("--out", o.batch.out, "results folder (default: the file's `output`)");
  c.batch
      ->add_option("--jobs", o.batch.jobs, "cases at a time (default: all cores; 1 per MPI rank)")
      ->check(CLI::PositiveNumber);
  c.batch->add_option("--max-steps", o.batch.max_steps, "--max-steps of every case")
      ->check(CLI::PositiveNumber);
  c.batch->add_flag("--no-vtk", o.no_vtk, "cases write no VTK series");

  c.calibrate = cli.add_subcommand(
      "calibrate", "fit model parameters to laboratory targets (also under mpirun)");
  c.calibrate->add_option("calibration_file", o.calibrate.file, "calibration file (.toml)")
      ->required();
  c.calibrate->add_option("--out", o.calibrate.out,
                          "results folder (default: the file's `output`)");
  c.calibrate
      ->add_option("--jobs", o.calibrate.jobs,
                   "runs at a time (default: all cores; 1 per MPI rank)")
      ->check(CLI::PositiveNumber);
  c.calibrate->add_flag(
      "--check", o.calibrate.check,
      "validate the file and its parameter bounds against the models, run nothing");

  c.laws = cli.add_subcommand(
      "laws", "print the contact laws' model-file keys (docs/model-file.md holds the same)");
}

// run, check, build: the model file read, its specimen made, then the command's own part.
int model_command(const Options& o, const Commands& c) {
  const io::ModelConfig cfg = run::read_model_file(o.model_path, parse_sets(o.sets));
  const geometry::Tessellation specimen = run::make_specimen(cfg);
  const fs::path out =
      o.out_dir.empty() ? fs::path("results") / fs::path(o.model_path).stem() : fs::path(o.out_dir);
  if (c.check->parsed()) {
    print_report(specimen, cfg);
    fmt::print("{}: ok ({} blocks, {})\n", o.model_path, specimen.blocks.size(),
               cfg.load_path.stages.empty()
                   ? fmt::format("a [{}] test", run::driver_name(cfg))
                   : fmt::format("{} stages", cfg.load_path.stages.size()));
    return 0;
  }
  if (!prepare_out(out)) return bad_input;
  print_report(specimen, cfg);
  if (c.build->parsed()) {
    io::write_specimen(out / "specimen.vsp", specimen, run::describe_contacts(cfg, specimen));
    fmt::print("specimen written to {}\n", (out / "specimen.vsp").string());
    return 0;
  }
  const run::RunOptions options{out, o.max_steps, !o.no_vtk, true, o.stop_at_step, {}};
  const run::RunSummary s = run::run_model(cfg, specimen, options, parse_sets(o.sets));
  print_outcome(o.model_path, s, out);
  return s.exit_code;
}

// run, resume, check, build, with their errors as exit codes.
int run_command(const Options& o, const Commands& c) {
  if (o.threads > 0) omp_set_num_threads(o.threads);
  try {
    if (c.resume->parsed()) {
      const run::RunSummary s = run::resume_run(o.resume_dir, o.stop_at_step, true);
      print_outcome(o.resume_dir, s, o.resume_dir);
      return s.exit_code;
    }
    return model_command(o, c);
  } catch (const checkpoint::CheckpointError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return bad_input;
  } catch (const io::ModelFileError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return bad_input;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Spin briefly, then sleep: on a shared 2-core machine long spinning stalls every barrier.
  setenv("GOMP_SPINCOUNT", "20000", 0);
  CLI::App cli{"vorodec: 2D Voronoi distinct element code for rock mechanics"};
  cli.set_version_flag("--version", std::string("vorodec ") + VORODEC_VERSION);
  cli.require_subcommand(1);
  Options o;
  Commands c{};
  add_model_commands(cli, o, c);
  add_workflow_commands(cli, o, c);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : bad_input;
  }
  if (c.batch->parsed()) {
    o.batch.write_vtk = !o.no_vtk;
    return workflows::run_batch(o.batch);
  }
  if (c.calibrate->parsed()) return workflows::calibrate(o.calibrate);
  if (c.laws->parsed()) {
    fmt::print("{}", laws::law_reference());
    return 0;
  }
  return run_command(o, c);
}
