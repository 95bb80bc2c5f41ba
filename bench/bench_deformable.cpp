// The deformable-block step on the default specimen (models/ucs_marble.toml, 1,302 blocks) zoned
// into constant-strain triangles, against the same specimen with rigid blocks. Reports zone updates
// per second (zu/s, per core), the cost of the zone kernel alone (stress + gridpoint forces), and
// the whole step's time, so that the deformable/rigid cost ratio can be read off.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/model/zoning.hpp"

using namespace vorodec;

namespace {

// Zone size in micrometres as the first argument (0: rigid blocks), threads as the second.
io::ModelConfig model(std::int64_t zone_um) {
  io::ModelConfig cfg =
      run::read_model_file(std::string(VORODEC_SOURCE_DIR) + "/models/ucs_marble.toml");
  if (zone_um > 0) cfg.deformable = {true, 1e-6 * static_cast<double>(zone_um), 60e9, 0.25};
  return cfg;
}

run::PreparedModel loaded(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const io::ModelConfig cfg = model(state.range(0));
  run::PreparedModel pm = run::prepare_model(cfg, run::make_specimen(cfg));
  const loading::SpecimenBoundary boundary(*pm.model);
  boundary.set_platen_velocity(*pm.model, 0.05);
  for (int i = 0; i < 300; ++i) pm.solver->step();  // load the contacts first
  return pm;
}

void counters(benchmark::State& state, const run::PreparedModel& pm, double per_step) {
  const double threads = static_cast<double>(state.range(1));
  const double steps = static_cast<double>(state.iterations());
  state.counters["zones"] = static_cast<double>(pm.model->zoning.zones.size());
  state.counters["contacts"] = static_cast<double>(pm.model->contacts.size());
  state.counters["zu/s/core"] =
      benchmark::Counter(per_step * steps / threads, benchmark::Counter::kIsRate);
  state.counters["steps/s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
}

// One whole explicit step (detection amortised). Rigid (zone size 0): the reference.
void BM_Step(benchmark::State& state) {
  run::PreparedModel pm = loaded(state);
  for (auto _ : state) pm.solver->step();
  counters(state, pm, static_cast<double>(pm.model->zoning.zones.size()));
}

// The zone kernel alone: strains, stresses and forces of every zone, added to its gridpoints.
void BM_ZoneForces(benchmark::State& state) {
  run::PreparedModel pm = loaded(state);
  std::vector<double> fx, fy;
  for (auto _ : state) {
    model::zone_forces(pm.model->zoning, fx, fy);
    benchmark::DoNotOptimize(fx.data());
  }
  counters(state, pm, static_cast<double>(pm.model->zoning.zones.size()));
}

}  // namespace

BENCHMARK(BM_Step)
    ->Args({0, 1})
    ->Args({1000, 1})
    ->Args({500, 1})
    ->Args({0, 2})
    ->Args({1000, 2})
    ->Args({500, 2})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ZoneForces)
    ->Args({1000, 1})
    ->Args({500, 1})
    ->Args({500, 2})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
