#include "model_runs.hpp"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "cases.hpp"
#include "vorodec/io/json.hpp"

namespace vorodec::verification {

namespace {
std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> cells;
  for (std::size_t p = 0; p <= text.size();) {
    const auto q = std::min(text.find(',', p), text.size());
    cells.push_back(text.substr(p, q - p));
    p = q + 1;
  }
  return cells;
}
}  // namespace

ModelRun run_model(const std::string& binary, const std::filesystem::path& model,
                   const std::filesystem::path& out, const std::string& args) {
  const auto t0 = std::chrono::steady_clock::now();
  std::filesystem::create_directories(out);
  const std::string cmd = fmt::format("{} run {} --no-vtk --out {} {} > {}/log.txt 2>&1", binary,
                                      model.string(), out.string(), args, out.string());
  ModelRun r;
  r.out = out;
  const int status = std::system(cmd.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(out / "summary.json");
  r.summary = {std::istreambuf_iterator<char>(in), {}};
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string set_arguments(const std::filesystem::path& model) {
  std::ifstream in(model);
  std::string args;
  for (std::string line; std::getline(in, line) && line.rfind('[', 0) != 0;) {
    const auto eq = line.find(" = "), dot = line.find('.');
    if (line.empty() || line[0] == '#' || eq == std::string::npos || dot > eq) continue;
    std::string value = line.substr(eq + 3, line.find('#') - eq - 3);
    value.erase(value.find_last_not_of(' ') + 1);
    args += fmt::format(" --set {}={}", line.substr(0, eq), value);
  }
  return args;
}

CaseResult relative(std::string id, std::string name, std::string reference, double expected,
                    double measured, double tolerance, std::string settings, double seconds) {
  CaseResult c{std::move(id),
               std::move(name),
               std::move(reference),
               expected,
               measured,
               std::abs(measured - expected) / std::abs(expected),
               tolerance,
               std::move(settings),
               seconds};
  if (!std::isfinite(c.error)) c.error = 1.0;
  return c;
}

namespace {

// The first value named `key`, depth first in the file's order; null if none.
io::Json first_named(const io::Json& j, const std::string& key) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      if (k == key) return v;
      if (io::Json found = first_named(v, key); !found.is_null()) return found;
    }
  } else if (j.is_array()) {
    for (const auto& v : j)
      if (io::Json found = first_named(v, key); !found.is_null()) return found;
  }
  return nullptr;
}

io::Json first_named(const std::string& json, const std::string& key) {
  const io::Json doc = io::Json::parse(json, nullptr, false);
  return doc.is_discarded() ? io::Json() : first_named(doc, key);
}

}  // namespace

double json_number(const std::string& json, const std::string& key) {
  const io::Json v = first_named(json, key);
  return v.is_number() ? v.get<double>() : std::nan("");
}

std::string json_string(const std::string& json, const std::string& key) {
  const io::Json v = first_named(json, key);
  return v.is_string() ? v.get<std::string>() : std::string();
}

int Table::column(const std::string& name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

double Table::number(std::size_t row, const std::string& name) const {
  const int c = column(name);
  if (c < 0 || row >= rows.size() || static_cast<std::size_t>(c) >= rows[row].size())
    return std::nan("");
  const std::string& cell = rows[row][static_cast<std::size_t>(c)];
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  return end == cell.c_str() ? std::nan("") : v;
}

Table read_table(const std::filesystem::path& csv) {
  Table t;
  std::ifstream in(csv);
  std::string line;
  if (std::getline(in, line)) t.header = split(line);
  while (std::getline(in, line))
    if (!line.empty()) t.rows.push_back(split(line));
  return t;
}

CaseResult energy_balance(const std::string& id, const ModelRun& run, const std::string& settings) {
  CaseResult e{id,
               "energy balance at the end of the run (imbalance / boundary work)",
               "boundary work = contact strain + kinetic + damping + friction + breakage",
               0,
               0,
               1.0,
               0.01,
               settings,
               run.seconds};
  const Table h = read_table(run.out / "history.csv");
  if (h.rows.empty()) return e;
  const std::size_t last = h.rows.size() - 1;
  const auto column = [&](const char* name) { return h.number(last, name); };
  const double work = column("boundary_work");
  double stored = column("strain_energy") + column("kinetic_energy") + column("damping_energy") +
                  column("friction_energy") + column("breakage_energy");
  if (h.column("zone_stress_yy") >= 0)  // deformable blocks: strain_energy holds the zones'
    e.reference =
        "boundary work = contact and zone strain + kinetic + damping + friction + breakage";
  if (h.column("viscous_energy") >= 0) {  // Burger's contacts: their dashpots' work
    stored += column("viscous_energy");
    e.reference += " + viscous";
  }
  if (std::isfinite(work) && std::isfinite(stored) && work != 0) {
    e.measured = (work - stored) / work;
    e.error = std::abs(e.measured);
  }
  return e;
}

CaseResult half_rate_ucs(const std::string& id, const std::string& binary,
                         const std::filesystem::path& model, const ModelRun& run,
                         const std::filesystem::path& half_out) {
  const ModelRun h = run_model(binary, model, half_out, "--set stage[0].platen_velocity=2.5e-3");
  CaseResult c{id,
               "UCS at 5e-3 m/s against UCS at 2.5e-3 m/s",
               "converged-rate reference: the same model at half the loading rate",
               json_number(h.summary, "peak_stress_Pa"),
               json_number(run.summary, "peak_stress_Pa"),
               0,
               0.02,
               "half rate: 2.5e-3 m/s",
               h.seconds};
  c.error = std::abs(c.measured - c.expected) / c.expected;
  if (std::isnan(c.error)) c.error = 1.0;
  return c;
}

}  // namespace vorodec::verification
