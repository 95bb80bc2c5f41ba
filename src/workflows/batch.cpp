#include "vorodec/workflows/batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <thread>

#include "case_runner.hpp"
#include "cluster.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/io/atomic_file.hpp"
#include "vorodec/workflows/batch_file.hpp"

namespace vorodec::workflows {

namespace fs = std::filesystem;

namespace {

constexpr int bad_input = 2, some_case_failed = 5;

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + '"';
}

std::string header(const BatchPlan& plan) {
  std::string h = "case,model";
  for (const std::string& key : plan.columns) h.append(",").append(csv_field(key));
  return h +
         ",exit_code,status,peak_stress_Pa,peak_passed,youngs_modulus_Pa,poisson_ratio,steps,"
         "cracks_tensile,cracks_shear,wall_time_s\n";
}

std::string row(const BatchPlan& plan, std::size_t i, const CaseOutcome& o, const fs::path& out) {
  const BatchCase& c = plan.cases[i];
  const io::Json summary = read_summary(out / c.name / "summary.json");
  const std::string status = summary.is_null() ? fmt::format("no summary, see {}/log.txt", c.name)
                                               : summary.value("status", std::string());
  // A number as summary.json rounds it (significant digits), or empty without a summary.
  const auto number = [&](const char* name, int digits) {
    const io::Json v = summary_value(summary, name);
    if (summary.is_null()) return std::string();
    if (v.is_boolean()) return std::string(v.get<bool>() ? "true" : "false");
    if (v.is_number_integer()) return fmt::format("{}", v.get<long>());
    return v.is_number() ? fmt::format("{:.{}g}", v.get<double>(), digits) : std::string("null");
  };
  // Appends only: GCC 12 warns (-Wrestrict, falsely) about "," + std::string here.
  std::string r = csv_field(c.name);
  r.append(",").append(csv_field(c.model.string()));
  for (const std::string& key : plan.columns)
    r.append(",").append(csv_field(override_value(c, key)));
  r += fmt::format(",{},{}", o.exit_code, csv_field(status));
  for (const auto& [key, digits] : {std::pair{"peak_stress_Pa", 8},
                                    {"peak_passed", 0},
                                    {"youngs_modulus_Pa", 8},
                                    {"poisson_ratio", 6},
                                    {"steps", 0},
                                    {"tensile", 0},
                                    {"shear", 0}})
    r.append(",").append(number(key, digits));
  return r + fmt::format(",{:.3f}\n", o.wall_seconds);
}

}  // namespace

int run_batch(const BatchOptions& options) {
  Cluster cluster;
  const bool lead = cluster.rank() == 0;
  if (cluster.refuse_without_mpi()) return bad_input;
  BatchPlan plan;
  try {
    plan = read_batch_file(options.batch_file);
    for (const BatchCase& c : plan.cases) run::read_model_file(c.model, c.overrides);
  } catch (const io::ModelFileError& e) {
    if (lead) fmt::print(stderr, "error: {}\n", e.what());
    return bad_input;  // every rank read the same files and stops here alike
  }
  const fs::path out = options.out.empty() ? plan.output : options.out;
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) {
    fmt::print(stderr, "error: results folder '{}' cannot be created\n", out.string());
    cluster.abort(bad_input);
  }
  int jobs = options.jobs;
  if (jobs <= 0)
    jobs =
        cluster.size() > 1 ? 1 : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::vector<std::size_t> mine;
  for (std::size_t i = static_cast<std::size_t>(cluster.rank()); i < plan.cases.size();
       i += static_cast<std::size_t>(cluster.size()))
    mine.push_back(i);
  const std::string who = cluster.size() > 1 ? fmt::format("rank {}: ", cluster.rank()) : "";
  if (lead)
    fmt::print("{}: {} cases, {} process(es) x {} at a time, results in {}/\n",
               options.batch_file.string(), plan.cases.size(), cluster.size(), jobs, out.string());

  // Rows travel as "index<TAB>exit code<TAB>row" lines, so rank 0 can put them in case order.
  std::string rows;
  try {
    const CaseOptions case_options{options.max_steps, options.write_vtk, options.executable};
    for (const auto& [i, o] : run_cases(plan.cases, mine, out, case_options, jobs, who))
      rows += fmt::format("{}\t{}\t{}", i, o.exit_code, row(plan, i, o, out));
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}error: {}\n", who, e.what());
    cluster.abort(1);
  }
  const std::vector<std::string> gathered = cluster.gather(rows);
  // Only rank 0 reports failed cases: mpirun kills the job at a rank's non-zero exit, perhaps
  // before rank 0 has written the table.
  if (!lead) return 0;

  std::map<std::size_t, std::string> ordered;
  bool all_ok = true;
  for (const std::string& text : gathered) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
      const auto tab1 = line.find('\t'), tab2 = line.find('\t', tab1 + 1);
      ordered[std::stoul(line.substr(0, tab1))] = line.substr(tab2 + 1);
      all_ok &= line.substr(tab1 + 1, tab2 - tab1 - 1) == "0";
    }
  }
  std::string table = header(plan);
  for (const auto& [i, r] : ordered) table += r + '\n';
  io::write_file_atomically(out / "results.csv", table);
  fs::copy_file(options.batch_file, out / "batch.toml", fs::copy_options::overwrite_existing, ec);
  fmt::print("results.csv: {} rows in {}/\n", ordered.size(), out.string());
  return all_ok ? 0 : some_case_failed;
}

}  // namespace vorodec::workflows
