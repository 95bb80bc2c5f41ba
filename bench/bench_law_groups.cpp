// What an unused law costs: the default model's step with its two law groups (joints, platens)
// against the same step with a third, instantiated law group that no contact uses.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/model/build.hpp"

using namespace vorodec;

namespace {

void BM_DefaultModelStepLawGroups(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const io::ModelConfig cfg =
      run::read_model_file(std::string(VORODEC_SOURCE_DIR) + "/models/ucs_marble.toml");
  const auto tess = run::make_specimen(cfg);
  model::Model m = model::build_model(tess, {cfg.density, cfg.rounding_length, true});
  std::vector<std::unique_ptr<laws::LawGroup>> groups;
  for (const io::LawChoice* choice : {&cfg.joints, &cfg.platens})
    groups.push_back(laws::find_law(choice->name)->make(choice->params, cfg.seed));
  if (state.range(0))  // instantiated, but no group pair in the table selects it
    groups.push_back(laws::find_law("linear_elastic")
                         ->make({{"jkn", model::Distribution::constant(1e13)},
                                 {"jks", model::Distribution::constant(1e13)}},
                                cfg.seed));
  solver::LawTable table;  // as run::prepare_model: specimen-specimen 0, specimen-platen 1
  for (std::size_t p : {1u, 2u}) table.law[0][p] = table.law[p][0] = 1;
  table.law[0][0] = 0;
  solver::SolverSettings settings = cfg.solver;
  settings.contact_tolerance = cfg.rounding_length;
  solver::Solver solver(m, std::move(groups), table, settings);
  solver.initialise();
  const loading::SpecimenBoundary boundary(m);
  boundary.set_platen_velocity(m, 0.05);
  for (int i = 0; i < 300; ++i) solver.step();  // load the contacts first
  for (auto _ : state) solver.step();
  state.counters["law_groups"] = static_cast<double>(solver.laws().size());
  state.counters["contacts"] = static_cast<double>(m.contacts.size());
}

}  // namespace

BENCHMARK(BM_DefaultModelStepLawGroups)
    ->ArgNames({"unused_group", "threads"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({0, 2})
    ->Args({1, 2})
    ->Repetitions(5)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
