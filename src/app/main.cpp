// The vorodec command: run, resume, check and build model files, run batches, calibrate.
#include <fmt/format.h>
#include <omp.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>

#include "vorodec/app/batch.hpp"
#include "vorodec/app/calibrate.hpp"
#include "vorodec/app/simulation.hpp"
#include "vorodec/checkpoint/checkpoint_file.hpp"
#include "vorodec/io/model_file.hpp"
#include "vorodec/io/specimen_file.hpp"

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
  if (cfg.specimen_file) fmt::print("specimen loaded from {}\n", cfg.specimen_file->string());
  fmt::print("{}", geometry::format_report(t.report));
  if (cfg.grains) {
    double total = 0;
    for (const double a : t.mineral_area) total += a;
    fmt::print(
        "  grains: {}, {} sub-blocks ({})\n", t.grain_mineral.size(), t.blocks.size(),
        cfg.grains->settings.sub_blocks == geometry::SubBlocks::trigon ? "trigon" : "voronoi");
    for (std::size_t m = 0; m < cfg.grains->minerals.size(); ++m)
      fmt::print("  mineral {}: area fraction {:.4f} (requested {:.4f})\n",
                 cfg.grains->minerals[m].name, t.mineral_area[m] / total,
                 cfg.grains->minerals[m].fraction);
  }
  for (const auto& w : t.report.warnings) fmt::print(stderr, "warning: specimen: {}\n", w);
}

void print_outcome(const std::string& what, const app::RunSummary& s, const fs::path& out) {
  if (s.exit_code == app::kStoppedForResume) {
    fmt::print("{}: {} after {:.1f} s; continue with `vorodec resume {}`\n", what, s.status,
               s.wall_seconds, out.string());
    return;
  }
  fmt::print(
      "{}: {} after {} steps in {:.1f} s; peak stress {:.2f} MPa,{} E {:.2f} GPa, nu {:.3f}; "
      "cracks {} tensile, {} shear\nresults in {}/ (history.csv, summary.json, cracks.csv, "
      "vtk/*.pvd)\n",
      what, s.status, s.steps, s.wall_seconds, s.peak_stress / 1e6,
      s.tensile_strength > 0
          ? fmt::format(" tensile strength {:.2f} MPa,", s.tensile_strength / 1e6)
          : "",
      s.youngs_modulus / 1e9, s.poisson_ratio, s.cracks_tensile, s.cracks_shear, out.string());
}

}  // namespace

int main(int argc, char** argv) {
  // Spin briefly, then sleep: on a shared 2-core machine long spinning stalls every barrier.
  setenv("GOMP_SPINCOUNT", "20000", 0);
  CLI::App cli{"vorodec: 2D Voronoi distinct element code for rock mechanics"};
  cli.set_version_flag("--version", std::string("vorodec ") + VORODEC_VERSION);
  cli.require_subcommand(1);
  std::string model_path, out_dir;
  int threads = 0;
  long max_steps = 0;
  bool no_vtk = false;
  std::vector<std::string> sets;
  app::BatchOptions batch_options;
  const auto add_set = [&sets](CLI::App* sub) {
    sub->add_option("--set", sets,
                    "override a model-file key, KEY=VALUE with a TOML value "
                    "(loading.confining_stress=5e6); repeatable")
        ->expected(1)
        ->take_all();
  };

  auto* run = cli.add_subcommand("run", "run a model file to the end of its load path");
  run->add_option("model", model_path, "model file (.toml)")->required();
  run->add_option("--out", out_dir, "results folder (default: results/<model name>)");
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::PositiveNumber);
  run->add_option("--max-steps", max_steps, "stop after this many steps (short runs)")
      ->check(CLI::PositiveNumber);
  run->add_flag("--no-vtk", no_vtk, "do not write the VTK series");
  long stop_at_step = 0;
  run->add_option("--stop-at-step", stop_at_step,
                  "write a checkpoint at this step and stop (exit 6), for `vorodec resume`")
      ->check(CLI::PositiveNumber);
  add_set(run);

  std::string resume_dir;
  auto* resume = cli.add_subcommand("resume", "continue a stopped run from its checkpoint");
  resume->add_option("dir", resume_dir, "results folder of the stopped run")->required();
  resume->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::PositiveNumber);
  resume->add_option("--stop-at-step", stop_at_step, "stop again at this step (exit 6)")
      ->check(CLI::PositiveNumber);

  auto* check = cli.add_subcommand("check", "validate a model file and its specimen, run nothing");
  check->add_option("model", model_path, "model file (.toml)")->required();
  add_set(check);

  auto* build = cli.add_subcommand("build", "build the specimen and save it for `specimen.file`");
  build->add_option("model", model_path, "model file (.toml)")->required();
  build->add_option("--out", out_dir, "folder for specimen.vsp (default: results/<model name>)");

  auto* batch = cli.add_subcommand("batch", "run every case of a batch file (also under mpirun)");
  batch->add_option("batch_file", batch_options.batch_file, "batch file (.toml)")->required();
  batch->add_option("--out", batch_options.out, "results folder (default: the file's `output`)");
  batch
      ->add_option("--jobs", batch_options.jobs,
                   "cases at a time (default: all cores; 1 per MPI rank)")
      ->check(CLI::PositiveNumber);
  batch->add_option("--max-steps", batch_options.max_steps, "--max-steps of every case")
      ->check(CLI::PositiveNumber);
  batch->add_flag("--no-vtk", no_vtk, "cases write no VTK series");

  app::CalibrateOptions calibrate_options;
  auto* calibrate = cli.add_subcommand(
      "calibrate", "fit model parameters to laboratory targets (also under mpirun)");
  calibrate->add_option("calibration_file", calibrate_options.file, "calibration file (.toml)")
      ->required();
  calibrate->add_option("--out", calibrate_options.out,
                        "results folder (default: the file's `output`)");
  calibrate
      ->add_option("--jobs", calibrate_options.jobs,
                   "runs at a time (default: all cores; 1 per MPI rank)")
      ->check(CLI::PositiveNumber);
  calibrate->add_flag("--check", calibrate_options.check,
                      "validate the file and its parameter bounds against the models, run nothing");

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : bad_input;
  }
  if (batch->parsed()) {
    batch_options.write_vtk = !no_vtk;
    return app::run_batch(batch_options);
  }
  if (calibrate->parsed()) return app::calibrate(calibrate_options);
  if (threads > 0) omp_set_num_threads(threads);
  try {
    if (resume->parsed()) {
      const app::RunSummary s = app::resume_run(resume_dir, stop_at_step, true);
      print_outcome(resume_dir, s, resume_dir);
      return s.exit_code;
    }
    const io::ModelConfig cfg = io::read_model_file(model_path, parse_sets(sets));
    geometry::Tessellation specimen;
    try {
      specimen = app::make_specimen(cfg);
    } catch (const geometry::GeometryError& e) {
      fmt::print(stderr, "error: {}:{}: [specimen]: impossible geometry: {}\n", model_path,
                 cfg.specimen_line, e.what());
      return bad_input;
    }
    const fs::path out =
        out_dir.empty() ? fs::path("results") / fs::path(model_path).stem() : fs::path(out_dir);
    if (check->parsed()) {
      print_report(specimen, cfg);
      fmt::print("{}: ok ({} blocks, {})\n", model_path, specimen.blocks.size(),
                 cfg.shpb ? std::string("a pressure-bar test")
                          : fmt::format("{} stages", cfg.load_path.stages.size()));
      return 0;
    }
    if (!prepare_out(out)) return bad_input;
    print_report(specimen, cfg);
    if (build->parsed()) {
      io::write_specimen(out / "specimen.vsp", specimen, app::describe_contacts(cfg, specimen));
      fmt::print("specimen written to {}\n", (out / "specimen.vsp").string());
      return 0;
    }
    app::RunOptions options{out, max_steps, !no_vtk, true, stop_at_step};
    const app::RunSummary s = app::run_model(cfg, specimen, options, parse_sets(sets));
    print_outcome(model_path, s, out);
    return s.exit_code;
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
