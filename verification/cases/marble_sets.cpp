// The marble's hand set (models/ucs_marble.toml) against C3's calibrated set
// (models/ucs_marble_two_nu.toml) over five seeds: the evidence for which one ucs_marble.toml
// keeps.
#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cases.hpp"
#include "model_runs.hpp"

namespace vorodec::verification {

namespace {
namespace fs = std::filesystem;

constexpr std::array seeds{42, 43, 44, 45, 46};
constexpr std::array tests{"ucs_marble", "tension_marble", "brazilian_marble"};

struct Spread {
  double mean = 0, sd = 0;
  int failed = 0;  // runs that did not finish (left out of the mean)
};

Spread over_seeds(const std::vector<ModelRun>& runs, const std::string& key) {
  std::vector<double> v;
  Spread s;
  for (const ModelRun& r : runs) {
    const double x = json_number(r.summary, key);
    if (r.exit_code == 0 && std::isfinite(x))
      v.push_back(x);
    else
      ++s.failed;
  }
  if (v.empty()) return {std::nan(""), std::nan(""), s.failed};
  for (double x : v) s.mean += x / static_cast<double>(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(s.sd / static_cast<double>(v.size() - 1)) : 0;
  return s;
}

CaseResult judged(const std::string& name, const std::string& reference, double expected,
                  const Spread& s, double tolerance, const std::string& settings, double seconds) {
  return relative("C3", name, reference, expected, s.mean, tolerance, settings, seconds);
}
}  // namespace

std::vector<CaseResult> marble_sets_over_seeds(const std::string& source_dir,
                                               const std::string& binary) {
  const fs::path models = fs::path(source_dir) / "models";
  const fs::path out = fs::temp_directory_path() / "vorodec_verification/marble_sets";
  const std::array<std::string, 2> labels{"hand set", "two-nu set"};
  const std::array<std::string, 2> sets{"", set_arguments(models / "ucs_marble_two_nu.toml")};
  // runs[set][test][seed], two at a time on one thread each.
  std::vector<ModelRun> runs(sets.size() * tests.size() * seeds.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t j; (j = next++) < runs.size();) {
      const std::size_t set = j / (tests.size() * seeds.size());
      const std::size_t test = j / seeds.size() % tests.size();
      const int seed = seeds[j % seeds.size()];
      runs[j] = run_model(binary, models / (std::string(tests[test]) + ".toml"),
                          out / fmt::format("{}_{}_{}", set, tests[test], seed),
                          fmt::format("--threads 1 --set seed={}{}", seed, sets[set]));
    }
  };
  {
    std::thread other(work);
    work();
    other.join();
  }
  std::vector<CaseResult> r;
  const std::string table1 = "marble, UDEC Voronoi [Yu2023], Table 1";
  for (std::size_t set = 0; set < sets.size(); ++set) {
    const auto group = [&](std::size_t test) {
      const auto first =
          runs.begin() + static_cast<long>((set * tests.size() + test) * seeds.size());
      return std::vector<ModelRun>(first, first + static_cast<long>(seeds.size()));
    };
    const auto ucs = group(0), pull = group(1), disc = group(2);
    double seconds = 0;
    for (std::size_t t = 0; t < tests.size(); ++t)
      for (const ModelRun& run : group(t)) seconds += run.seconds;
    const std::string& label = labels[set];
    const auto settings = [&](const std::string& model, const Spread& s) {
      return fmt::format("models/{}.toml{}, seeds 42-46 (sd {:.3g}; {} runs did not finish)", model,
                         set == 1 ? " with the set of models/ucs_marble_two_nu.toml" : "", s.sd,
                         s.failed);
    };
    const Spread peak = over_seeds(ucs, "peak_stress_Pa"), e = over_seeds(ucs, "youngs_modulus_Pa"),
                 nu = over_seeds(ucs, "poisson_ratio"),
                 nu0 = over_seeds(ucs, "initial_poisson_ratio"),
                 direct = over_seeds(pull, "tensile_strength_Pa"),
                 e_pull = over_seeds(pull, "youngs_modulus_Pa"),
                 brazilian = over_seeds(disc, "tensile_strength_Pa");
    r.push_back(judged(label + ": UCS, mean of 5 seeds (Pa)", table1, 47.89e6, peak, 0.05,
                       settings("ucs_marble", peak), seconds));
    r.push_back(judged(label + ": Young's modulus, mean of 5 seeds (Pa)", table1, 29.22e9, e, 0.05,
                       settings("ucs_marble", e), seconds));
    r.push_back(judged(label + ": Poisson's ratio (40-60 % of peak), mean of 5 seeds", table1,
                       0.225, nu, 0.05, settings("ucs_marble", nu), seconds));
    r.push_back(judged(label + ": initial Poisson's ratio (10-30 % of peak), mean of 5 seeds",
                       "marble cyclic loading [Yu2023], B2: about 0.18 at the first loading", 0.18,
                       nu0, 0.10, settings("ucs_marble", nu0), seconds));
    r.push_back({"C3", label + ": direct tensile strength, mean of 5 seeds (Pa)",
                 "derived; the paper gives none", 0, direct.mean, 0, 0,
                 settings("tension_marble", direct), seconds, true});
    r.push_back(
        judged(label + ": Brazilian strength (flats 20 deg) against the direct tensile "
                       "strength, means of 5 seeds (Pa)",
               "elastic disc theory (Hondros 1959; ISRM 1978): equal for a brittle material",
               direct.mean, brazilian, 0.25, settings("brazilian_marble", brazilian), seconds));
    r.push_back(judged(label + ": Young's modulus in tension against in compression, means of 5 "
                               "seeds (Pa)",
                       "same contacts, linear before cracking: equal moduli", e.mean, e_pull, 0.05,
                       settings("tension_marble", e_pull), seconds));
  }
  return r;
}

}  // namespace vorodec::verification
