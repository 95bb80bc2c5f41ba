// The rigid-block Mohr-Coulomb step (geometry + laws + forces + integration, detection amortised
// as it runs) on the default model and on larger specimens of the same outline's block size.
// Reports contact updates per second (cu/s) per thread count and bytes per contact; and what a
// checkpoint of such a model costs to write.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <filesystem>

#include "specimens.hpp"
#include "vorodec/checkpoint/checkpoint_file.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"

using namespace vorodec;
using bench::default_model;
using bench::scaled_model;

namespace {

void run_steps(benchmark::State& state, const io::ModelConfig& cfg) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const auto tess = run::make_specimen(cfg);
  run::PreparedModel pm = run::prepare_model(cfg, tess);
  const loading::SpecimenBoundary boundary(*pm.model);
  boundary.set_platen_velocity(*pm.model, 0.05);
  for (int i = 0; i < 300; ++i) pm.solver->step();  // load the contacts first
  std::size_t updates = 0;
  for (auto _ : state) {
    pm.solver->step();
    updates += pm.model->contacts.size();
  }
  const double threads = static_cast<double>(state.range(1));
  state.counters["contacts"] = static_cast<double>(pm.model->contacts.size());
  state.counters["cu/s"] =
      benchmark::Counter(static_cast<double>(updates), benchmark::Counter::kIsRate);
  state.counters["cu/s/core"] =
      benchmark::Counter(static_cast<double>(updates) / threads, benchmark::Counter::kIsRate);
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  // Memory held per contact: record, force record (written only where a block is shared between
  // threads), gather index, shared-side flags, law properties and state.
  state.counters["bytes/contact"] =
      static_cast<double>(pm.solver->laws()[0]->bytes_per_contact() + sizeof(model::Contact) +
                          sizeof(model::ContactForce) + 2 * sizeof(std::uint32_t) + 1);
  // Per block: 15 doubles of state, loads and mass, group, flag, corner index, cos/sin, packed
  // kinematics; the solver's force sums, positions at the last detection and gather index; and
  // per corner its local corner and arc centre, shape constants and world positions.
  const auto& bl = pm.model->blocks;
  const double per_block = 15 * sizeof(double) + sizeof(model::Group) + 1 + sizeof(std::uint32_t) +
                           2 * sizeof(double) + sizeof(model::BlockKinematics) +
                           6 * sizeof(double) + sizeof(std::uint32_t);
  const double per_corner =
      2 * sizeof(model::Point) + sizeof(model::CornerShape) + sizeof(model::CornerWorld);
  state.counters["bytes/block"] = per_block + per_corner * static_cast<double>(bl.corner.size()) /
                                                  static_cast<double>(bl.size());
}

// `copies` 1e3-block specimens stepped in turn, `visit` steps each before the next, 200 steps each
// in all: every step runs the 1e3 code on 1e3 blocks, but the working set is `copies` times as
// large. With distinct seeds (second argument 1) the sequence of contact frames the branch
// predictor sees grows as well; with one seed (0) every copy repeats the same one. Against
// BM_ScaledStepFixed at copies x 1e3 blocks, visit 1 separates what the cache and the predictor
// cost from what the step's work costs as a specimen grows; visit > 1 is the best that stepping a
// large specimen `visit` steps at a time, cache-sized part by part, could do (no halo, no
// overhead).
void BM_CopiesStep(benchmark::State& state) {
  const auto copies = static_cast<std::size_t>(state.range(0));
  const bool distinct = state.range(1) != 0;
  const auto visit = static_cast<int>(state.range(2));
  omp_set_num_threads(1);
  std::vector<run::PreparedModel> models;
  for (std::size_t k = 0; k < copies; ++k) {
    io::ModelConfig cfg = scaled_model(1000);
    cfg.seed = cfg.tessellation.seed = distinct ? k + 1 : 1;
    const auto tess = run::make_specimen(cfg);
    models.push_back(run::prepare_model(cfg, tess));
    loading::SpecimenBoundary(*models.back().model).set_platen_velocity(*models.back().model, 0.05);
    for (int i = 0; i < 300; ++i) models.back().solver->step();
  }
  std::size_t updates = 0;
  for (auto _ : state) {  // one iteration: 200 steps per copy, as BM_ScaledStepFixed's 200 steps
    for (int round = 0; round < 200 / visit; ++round) {
      for (auto& pm : models) {
        for (int i = 0; i < visit; ++i) pm.solver->step();
        updates += static_cast<std::size_t>(visit) * pm.model->contacts.size();
      }
    }
  }
  state.counters["cu/s"] =
      benchmark::Counter(static_cast<double>(updates), benchmark::Counter::kIsRate);
}

// A checkpoint's model and solver part (blocks, contacts, laws, sums: all but the load path's and
// the outputs' few values) archived and written to disk (temporary name, fsync, rename).
void BM_CheckpointWrite(benchmark::State& state) {
  const io::ModelConfig cfg = scaled_model(static_cast<int>(state.range(0)));
  const auto tess = run::make_specimen(cfg);
  run::PreparedModel pm = run::prepare_model(cfg, tess);
  const loading::SpecimenBoundary boundary(*pm.model);
  boundary.set_platen_velocity(*pm.model, 0.05);
  for (int i = 0; i < 300; ++i) pm.solver->step();
  const auto file = std::filesystem::temp_directory_path() / "vorodec_bench_checkpoint.vck";
  std::size_t bytes = 0;
  for (auto _ : state)
    bytes = checkpoint::write_checkpoint(file, {}, [&](checkpoint::OutArchive& ar) {
      model::save_state(ar, *pm.model);
      pm.solver->save(ar);
    });
  std::filesystem::remove(file);
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["bytes/block"] =
      static_cast<double>(bytes) / static_cast<double>(pm.model->blocks.size());
}

void BM_DefaultModelStep(benchmark::State& state) {
  run_steps(state, default_model());
}
void BM_ScaledStep(benchmark::State& state) {
  run_steps(state, scaled_model(static_cast<int>(state.range(0))));
}

}  // namespace

BENCHMARK(BM_DefaultModelStep)->Args({1302, 1})->Args({1302, 2})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScaledStep)
    ->Args({1000, 1})
    ->Args({1000, 2})
    ->Args({10000, 1})
    ->Args({10000, 2})
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Unit(benchmark::kMillisecond);
// The same 200 steps after the preload at every size, so that every size is timed in the same
// (elastic) state: BM_ScaledStep times as many steps as fill its minimum time, which carries the
// small specimen thousands of steps further, up to its peak, than the large ones.
BENCHMARK(BM_ScaledStep)
    ->Name("BM_ScaledStepFixed")
    ->Args({1000, 1})
    ->Args({10000, 1})
    ->Args({100000, 1})
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CopiesStep)
    ->ArgsProduct({{1}, {1}, {1}})
    ->ArgsProduct({{10, 100}, {0, 1}, {1}})
    ->ArgsProduct({{10, 100}, {1}, {2, 4, 8}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CheckpointWrite)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
