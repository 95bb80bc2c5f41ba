#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cases.hpp"
#include "model_runs.hpp"

namespace vorodec::verification {

namespace {

namespace fs = std::filesystem;

struct Variant {
  std::string name, change;
  std::vector<std::pair<std::string, std::string>> edits;  // replace first occurrence
  long max_steps;
};

// e2e_small's generated specimen, to be replaced by a prepared specimen file.
constexpr const char* e2e_specimen =
    "width = 0.02           # m\nheight = 0.04          # m\nblock_count = 170\n"
    "lloyd_iterations = 2\nmin_edge_length = 2e-4 # m\n";

// A 10 x 20 grid of 2 mm squares with one row of height `sliver` at mid-height: each sliver
// block is (2 mm / sliver) times smaller in area and mass than its neighbours above and below.
void write_sliver_specimen(const fs::path& file, double sliver) {
  constexpr int nx = 10, rows = 21;
  constexpr double h = 2e-3;
  std::vector<double> y{0.0};
  for (int r = 0; r < rows; ++r) y.push_back(y.back() + (r == rows / 2 ? sliver : h));
  std::ofstream out(file);
  out << "vorodec-specimen 1\nvertices " << (nx + 1) * (rows + 1) << "\n";
  for (double yr : y)
    for (int i = 0; i <= nx; ++i) out << fmt::format("{:a} {:a}\n", i * h, yr);
  out << "blocks " << nx * rows << "\n";
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < nx; ++c) {
      const int v = r * (nx + 1) + c;
      out << fmt::format("4 {} {} {} {}\n", v, v + 1, v + nx + 2, v + nx + 1);
    }
}

// e2e_small with deformable blocks of intact marble and joints 55 times stiffer, never failing.
std::vector<std::pair<std::string, std::string>> deformable_stiff_joints(
    std::vector<std::pair<std::string, std::string>> more) {
  std::vector<std::pair<std::string, std::string>> edits{
      {"density = 2602         # kg/m^3",
       "density = 2602\ndeformable = true\nzone_size = 1e-3\nE = 70e9\nnu = 0.25"},
      {"jkn = 1.8e13", "jkn = 1e15"},
      {"jks = 7.3e12", "jks = 1e15"},
      {"mean = 14e6", "mean = 1e11"},
      {"mean = 24e6", "mean = 1e11"}};
  edits.insert(edits.end(), more.begin(), more.end());
  return edits;
}

std::string slurp(const fs::path& f) {
  std::ifstream in(f);
  return {std::istreambuf_iterator<char>(in), {}};
}

bool history_finite(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');)
      if (cell.find("nan") != std::string::npos || cell.find("inf") != std::string::npos)
        return false;
  }
  return true;
}

}  // namespace

std::vector<StabilityOutcome> stability_cases(const std::string& source_dir,
                                              const std::string& binary) {
  const std::vector<Variant> variants{
      {"stiff joints",
       "jkn and jks x 1e4 (the time step follows)",
       {{"jkn = 1.8e13", "jkn = 1.8e17"},
        {"jks = 7.3e12", "jks = 7.3e16"},
        {"time_step = 1e-6", "time_step = 0"}},
       3000},
      {"stiffness contrast 1e6",
       "jkn Weibull with shape 0.3 (ratios beyond 1e6 between contacts)",
       {{"jkn = 1.8e13", "jkn = { weibull_shape = 0.3, mean = 1.8e13 }"},
        {"time_step = 1e-6", "time_step = 0"}},
       3000},
      {"Weibull m = 1",
       "strengths with shape 1 (extreme heterogeneity)",
       {{"weibull_shape = 4.0, mean = 14e6", "weibull_shape = 1.0, mean = 14e6"},
        {"weibull_shape = 4.0, mean = 24e6", "weibull_shape = 1.0, mean = 24e6"}},
       40000},
      {"Weibull m = 50",
       "strengths with shape 50 (nearly uniform)",
       {{"weibull_shape = 4.0, mean = 14e6", "weibull_shape = 50.0, mean = 14e6"},
        {"weibull_shape = 4.0, mean = 24e6", "weibull_shape = 50.0, mean = 24e6"}},
       40000},
      {"impact 50 m/s",
       "platen at 50 m/s, no ramp, no density scaling",
       {{"platen_velocity = 0.02", "platen_velocity = 50.0"},
        {"ramp_time = 2e-4", "ramp_time = 0"},
        {"time_step = 1e-6", "time_step = 0"}},
       20000},
      {"confinement 200 MPa",
       "confining stress 200 MPa",
       {{"[[stage]]", "[loading]\nconfining_stress = 200e6\n\n[[stage]]"}},
       20000},
      {"no damping",
       "local damping 0 for the whole run",
       {{"local_damping = 0.8", "local_damping = 0.0"}},
       40000},
      {"falls apart",
       "no tension or cohesion: every contact is frictional from the start",
       {{"tension = { weibull_shape = 4.0, mean = 14e6 }", "tension = 0"},
        {"cohesion = { weibull_shape = 4.0, mean = 24e6 }", "cohesion = 0"}},
       40000},
      {"sliver blocks 1/100",
       "specimen file: 10 x 20 grid of 2 mm squares plus a 20 um row at mid-height (area and "
       "mass ratio to the neighbours 100)",
       {{e2e_specimen, "file = \"sliver100.vorodec\"\n"}},
       40000},
      {"near-zero mass 1e-6",
       "specimen file: the same grid with a 2 nm row (mass ratio 1e-6); no density scaling",
       {{e2e_specimen, "file = \"sliver1e6.vorodec\"\n"}, {"time_step = 1e-6", "time_step = 0"}},
       3000},
      {"fixed step above critical",
       "fixed_time_step = 1e-6 s instead of density scaling (above the critical step)",
       {{"time_step = 1e-6", "fixed_time_step = 1e-6"}},
       3000},
      // Issue 26: this once stopped within 700 steps (energy out of nothing) on a 511-block disc.
      {"deformable, stiff joints",
       "deformable blocks (1 mm zones, E 70 GPa), jkn = jks = 1e15 Pa/m, strengths out of reach, "
       "no density scaling, safety factor 0.2",
       deformable_stiff_joints({{"time_step = 1e-6", "time_step = 0\nsafety_factor = 0.2"}}), 5000},
      {"deformable, stiff joints, density scaling",
       "the same with density scaling (time_step 1e-6 s)", deformable_stiff_joints({}), 5000},
  };
  const fs::path model = fs::path(source_dir) / "tests/models/e2e_small.toml";
  const fs::path dir =
      fs::temp_directory_path() / ("vorodec_stability_" + std::to_string(getpid()));
  fs::create_directories(dir);
  write_sliver_specimen(dir / "sliver100.vorodec", 2e-5);
  write_sliver_specimen(dir / "sliver1e6.vorodec", 2e-9);
  std::vector<StabilityOutcome> out;
  std::size_t index = 0;
  for (const Variant& v : variants) {
    std::string text = slurp(model);
    for (const auto& [from, to] : v.edits) {
      const auto p = text.find(from);
      if (p == std::string::npos)  // a stale edit would silently test the unchanged model
        throw std::runtime_error(
            fmt::format("stability case '{}': no '{}' in {}", v.name, from, model.string()));
      text.replace(p, from.size(), to);
    }
    const fs::path file = dir / fmt::format("case{}.toml", index++);
    std::ofstream(file) << text;
    const fs::path run_dir = dir / file.stem();
    const auto t0 = std::chrono::steady_clock::now();
    const int status = std::system(
        fmt::format("{} run {} --no-vtk --threads 1 --max-steps {} --out {} > {}.log 2>&1", binary,
                    file.string(), v.max_steps, run_dir.string(), run_dir.string())
            .c_str());
    StabilityOutcome o;
    o.name = v.name;
    o.change = v.change;
    o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string summary = slurp(run_dir / "summary.json");
    o.status = json_string(summary, "status");
    o.steps = static_cast<long>(json_number(summary, "steps"));
    o.time_step = json_number(summary, "time_step_s");
    o.finite = history_finite(run_dir / "history.csv");
    out.push_back(o);
  }
  return out;
}

}  // namespace vorodec::verification
