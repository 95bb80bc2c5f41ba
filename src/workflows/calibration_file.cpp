#include "vorodec/workflows/calibration_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "plan_keys.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/input/override.hpp"
#include "vorodec/input/toml_section.hpp"

namespace vorodec::workflows {

// The model-file reader's tools: a batch or calibration file is read as model files are.
using namespace vorodec::io;

namespace {

// summary.json numbers a target may name (nested ones by their own name).
const std::vector<std::string> kSummaryQuantities = {"peak_stress_Pa",
                                                     "youngs_modulus_Pa",
                                                     "poisson_ratio",
                                                     "initial_poisson_ratio",
                                                     "tensile_strength_Pa",
                                                     "crack_initiation_stress_Pa",
                                                     "accelerating_crack_growth_stress_Pa",
                                                     "linear_youngs_modulus_Pa",
                                                     "failure_rate",
                                                     "failure_time_s",
                                                     "tensile",
                                                     "shear"};

std::string trimmed(std::string s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool folder_safe(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

// Names that go into CSV headers and markdown tables as they are.
bool column_safe(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string_view("_-.[]").find(c) != std::string_view::npos;
  });
}

std::string value_text(double v) {
  std::string t = fmt::format("{}", v);
  if (t.find_first_of(".en") == std::string::npos) t += ".0";
  return t;
}

// "c * a / b": numbers and parameter names joined by * and /.
Tie parse_tie(const std::string& key, const std::string& expression,
              const std::vector<CalibrationParameter>& parameters, TomlSection& sec) {
  Tie tie{key, 1.0, {}, {}, fmt::format("{}:{}", sec.file(), sec.find(key)->source().begin.line)};
  std::size_t pos = 0;
  bool divide = false;
  while (pos <= expression.size()) {
    const auto op = expression.find_first_of("*/", pos);
    const std::string token =
        trimmed(expression.substr(pos, op == std::string::npos ? std::string::npos : op - pos));
    if (token.empty())
      sec.fail(key, fmt::format("'{}': write numbers and parameter names joined by * and /",
                                expression));
    const auto p = std::find_if(parameters.begin(), parameters.end(),
                                [&](const CalibrationParameter& q) { return q.name == token; });
    if (p != parameters.end()) {
      (divide ? tie.divided_by : tie.times)
          .push_back(static_cast<std::size_t>(p - parameters.begin()));
    } else {
      char* end = nullptr;
      const double c = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(c) || c == 0)
        sec.fail(key, fmt::format("'{}' is neither a parameter nor a non-zero number", token));
      tie.constant = divide ? tie.constant / c : tie.constant * c;
    }
    if (op == std::string::npos) break;
    divide = expression[op] == '/';
    pos = op + 1;
  }
  if (tie.times.empty() && tie.divided_by.empty())
    sec.fail(key, "a tie must use at least one parameter (set a constant with the test's `set`)");
  return tie;
}

CalibrationParameter read_parameter(TomlSection& sec) {
  CalibrationParameter p;
  p.origin = fmt::format("{}:{}", sec.file(), sec.line());
  if (sec.has("key") == sec.has("name"))
    sec.fail("key", "give either `key` (a model-file key) or `name` (a free parameter for ties)");
  p.model_key = sec.has("key");
  p.name = sec.string(p.model_key ? "key" : "name", nullptr);
  if (!column_safe(p.name))
    sec.fail(p.model_key ? "key" : "name", "letters, digits and _ - . [ ] only");
  const std::string linear = "linear";
  const std::string scale = sec.string("scale", &linear);
  if (scale != "linear" && scale != "log") sec.fail("scale", "must be \"linear\" or \"log\"");
  p.log_scale = scale == "log";
  p.min = sec.number("min", NAN);
  p.max = sec.number("max", NAN);
  p.start = sec.number("start", NAN);
  if (!(p.min < p.max))
    sec.fail("max",
             fmt::format("bounds reversed or empty: min {} is not below max {}", p.min, p.max));
  if (p.log_scale && p.min <= 0) sec.fail("min", "a log-scale parameter needs min > 0");
  if (p.start < p.min || p.start > p.max)
    sec.fail("start", fmt::format("{} lies outside [{}, {}]", p.start, p.min, p.max));
  return p;
}

// A point of the run: { <column> = value } (its first crossing) or { stage = "name:end" }.
HistoryPoint read_history_point(TomlSection& sec, const char* key) {
  TomlSection at = sec.sub(key);
  if (at.table().size() != 1)
    sec.fail(key, "give one column: { time = 3600.0 } or { stage = \"load:end\" }");
  HistoryPoint p{std::string(at.table().begin()->first.str())};
  if (p.column == "stage")
    p.stage = at.string("stage", nullptr);
  else
    p.value = at.number(p.column, NAN);
  return p;
}

// quantity = "history.<column>" with at = { <column> = value } or at = { stage = "name:end" },
// and optionally from = { ... } (the change between the two points).
void read_history_quantity(TomlSection& sec, CalibrationTarget& t) {
  t.kind = TargetKind::history;
  t.reads.history = true;
  t.reads.name = t.quantity.substr(std::string("history.").size());
  if (t.reads.name.empty()) sec.fail("quantity", "history.<column>: name a history.csv column");
  if (!sec.has("at"))
    sec.fail("at",
             "a history quantity needs `at`: { time = 3600.0 }, { axial_strain = 0.002 }, "
             "{ axial_stress = 100e6 } (any column, its first crossing) or { stage = "
             "\"load:end\" }");
  t.reads.at = read_history_point(sec, "at");
  if (sec.has("from")) t.reads.from = read_history_point(sec, "from");
}

CalibrationTarget read_target(TomlSection& sec, const std::vector<CalibrationTest>& tests) {
  CalibrationTarget t;
  t.name = sec.string("name", nullptr);
  if (!folder_safe(t.name)) sec.fail("name", "letters, digits, _ and - only");
  t.origin = fmt::format("{}:{}: target '{}'", sec.file(), sec.line(), t.name);
  t.quantity = sec.string("quantity", nullptr);
  t.reads.name = t.quantity;
  if (t.quantity == "cohesion_Pa")
    t.kind = TargetKind::envelope_cohesion;
  else if (t.quantity == "friction_angle_deg")
    t.kind = TargetKind::envelope_friction;
  else if (t.quantity.starts_with("history."))
    read_history_quantity(sec, t);
  else if (t.quantity.find('.') == std::string::npos &&
           std::find(kSummaryQuantities.begin(), kSummaryQuantities.end(), t.quantity) ==
               kSummaryQuantities.end())
    sec.fail("quantity",
             fmt::format("'{}' is not produced by any test: a summary.json number ({}, or any "
                         "by its dotted path: acoustic_emission.b_value), history.<column> with "
                         "`at`, or an envelope's cohesion_Pa or friction_angle_deg",
                         t.quantity, fmt::join(kSummaryQuantities, ", ")));
  for (const char* key : {"at", "from"})
    if (t.kind != TargetKind::history && sec.has(key))
      sec.fail(key, "only a history.<column> quantity is read `at` (or `from`) a point of the run");
  const auto find_test = [&](const std::string& name, std::string_view key) {
    const auto it = std::find_if(tests.begin(), tests.end(),
                                 [&](const CalibrationTest& c) { return c.name == name; });
    if (it == tests.end()) sec.fail(key, fmt::format("no [[test]] is named '{}'", name));
    return static_cast<std::size_t>(it - tests.begin());
  };
  const bool envelope =
      t.kind == TargetKind::envelope_cohesion || t.kind == TargetKind::envelope_friction;
  if (envelope) {
    const toml::node* n = sec.node("tests");
    const toml::array* a = n ? n->as_array() : nullptr;
    if (!a) sec.fail("tests", "an envelope target needs `tests`, the names of two or more tests");
    std::set<double> confinements;
    for (const toml::node& v : *a) {
      const auto name = v.value_exact<std::string>();
      if (!name) sec.fail("tests", "must be an array of test names");
      t.tests.push_back(find_test(*name, "tests"));
      confinements.insert(tests[t.tests.back()].confining_stress);
    }
    if (confinements.size() < 2)
      sec.fail("tests", "an envelope needs tests at two or more different confining stresses");
  } else {
    t.tests.push_back(find_test(sec.string("test", nullptr), "test"));
  }
  t.value = sec.number("value", NAN);
  t.weight = sec.positive("weight", 1.0);
  if (sec.has("tolerance") == sec.has("absolute_tolerance"))
    sec.fail("tolerance",
             "give either `tolerance` (relative, 0.03 = 3 %) or `absolute_tolerance` (in the "
             "quantity's unit)");
  t.absolute = sec.has("absolute_tolerance");
  t.tolerance = sec.positive(t.absolute ? "absolute_tolerance" : "tolerance", NAN);
  if (!t.absolute && t.value == 0)
    sec.fail("tolerance", "a relative tolerance needs a non-zero value: use absolute_tolerance");
  return t;
}

// Every test's model file must accept each parameter at its bounds (the others at their starts).
void check_bounds(const CalibrationPlan& plan, const toml::array& list, const std::string& file) {
  std::vector<double> values;
  for (const CalibrationParameter& p : plan.parameters) values.push_back(p.start);
  for (std::size_t i = 0; i < plan.parameters.size(); ++i) {
    for (const char* bound : {"min", "max"}) {
      std::vector<double> v = values;
      v[i] = bound[1] == 'i' ? plan.parameters[i].min : plan.parameters[i].max;
      for (std::size_t t = 0; t < plan.tests.size(); ++t) {
        try {
          run::read_model_file(plan.tests[t].model, run_overrides(plan, t, plan.seeds.front(), v));
        } catch (const ModelFileError& e) {
          TomlSection sec(*list[i].as_table(), fmt::format("parameter[{}]", i), file);
          sec.fail(bound,
                   fmt::format("{} = {}: test '{}' refuses it: {}", plan.parameters[i].name, v[i],
                               plan.tests[t].name, e.reason().empty() ? e.what() : e.reason()));
        }
      }
    }
  }
}

std::vector<std::uint64_t> read_seeds(TomlSection& top) {
  std::vector<std::uint64_t> seeds;
  const toml::node* list = top.node("seeds");
  if (!list || !list->is_array() || list->as_array()->empty())
    top.fail("seeds", "give a non-empty array of seeds, e.g. [1, 2, 3]");
  for (const toml::node& s : *list->as_array()) {
    const auto v = s.value_exact<std::int64_t>();
    if (!v || *v < 0) top.fail_at(&s, "seeds", "seeds are non-negative integers");
    seeds.push_back(static_cast<std::uint64_t>(*v));
  }
  if (std::set<std::uint64_t>(seeds.begin(), seeds.end()).size() != seeds.size())
    top.fail("seeds", "a seed is listed twice");
  return seeds;
}

void read_budget(TomlSection budget, CalibrationPlan& plan) {
  if (!budget.has("runs")) budget.fail("runs", "required key is missing");
  plan.max_runs = budget.integer("runs", 0, 1);
  plan.max_wall_seconds = budget.positive("wall_time", NAN);
  budget.finish();
}

// The [[test]] tables; each test's model file is read for its confining stress.
std::vector<CalibrationTest> read_tests(TomlSection& top, const std::filesystem::path& file) {
  std::vector<CalibrationTest> list;
  const toml::node* tests = top.node("test");
  if (!tests || !tests->is_array_of_tables() || tests->as_array()->empty())
    top.fail("test", "give one or more [[test]] tables (name, model, set)");
  for (std::size_t i = 0; i < tests->as_array()->size(); ++i) {
    TomlSection sec(*tests->as_array()->get(i)->as_table(), fmt::format("test[{}]", i), top.file());
    CalibrationTest t;
    t.name = sec.string("name", nullptr);
    if (!folder_safe(t.name)) sec.fail("name", "letters, digits, _ and - only");
    for (const CalibrationTest& u : list)
      if (u.name == t.name) sec.fail("name", fmt::format("two tests are named '{}'", t.name));
    t.model = sec.string("model", nullptr);
    if (t.model.is_relative())
      t.model = (std::filesystem::absolute(file).parent_path() / t.model).lexically_normal();
    if (!std::filesystem::is_regular_file(t.model))
      sec.fail("model", fmt::format("model file '{}' does not exist", t.model.string()));
    t.overrides = read_set(sec);
    sec.finish();
    t.confining_stress = run::read_model_file(t.model, t.overrides).load_path.confining_stress;
    list.push_back(std::move(t));
  }
  return list;
}

// The [[parameter]] tables (their list returned, for later messages); the names of the targets
// each scales go into `scale_names`, to be found once the targets are read.
const toml::array& read_parameters(TomlSection& top, CalibrationPlan& plan,
                                   std::vector<std::vector<std::string>>& scale_names) {
  const toml::node* parameters = top.node("parameter");
  if (!parameters || !parameters->is_array_of_tables() || parameters->as_array()->empty())
    top.fail("parameter", "give one or more [[parameter]] tables (key, min, max, start)");
  const toml::array& parameter_list = *parameters->as_array();
  for (std::size_t i = 0; i < parameter_list.size(); ++i) {
    TomlSection sec(*parameter_list[i].as_table(), fmt::format("parameter[{}]", i), top.file());
    CalibrationParameter p = read_parameter(sec);
    for (const CalibrationParameter& q : plan.parameters)
      if (q.name == p.name) sec.fail("key", fmt::format("'{}' is varied twice", p.name));
    scale_names.emplace_back();
    if (const toml::node* s = sec.node("scales")) {
      if (!s->is_array()) sec.fail("scales", "must be an array of target names");
      for (const toml::node& v : *s->as_array()) {
        const auto n = v.value_exact<std::string>();
        if (!n) sec.fail("scales", "must be an array of target names");
        scale_names.back().push_back(*n);
      }
    }
    sec.finish();
    plan.parameters.push_back(std::move(p));
  }
  return parameter_list;
}

// [tie]: "model key" = "expression" of the parameters.
void read_ties(TomlSection& top, CalibrationPlan& plan) {
  const toml::node* ties = top.node("tie");
  if (!ties) return;
  if (!ties->is_table()) top.fail("tie", "must be a table of \"model key\" = \"expression\"");
  TomlSection sec(*ties->as_table(), "tie", top.file());
  for (const auto& [k, v] : *ties->as_table()) {
    const std::string key(k.str());
    const auto expression = v.value_exact<std::string>();
    if (!expression) sec.fail(key, "must be an expression in quotes, e.g. \"joints.jkn / 2.6\"");
    for (const CalibrationParameter& p : plan.parameters)
      if (p.name == key) sec.fail(key, "is a parameter already; a key is varied or tied");
    sec.node(key);
    plan.ties.push_back(parse_tie(key, *expression, plan.parameters, sec));
  }
}

void read_targets(TomlSection& top, CalibrationPlan& plan) {
  const toml::node* targets = top.node("target");
  if (!targets || !targets->is_array_of_tables() || targets->as_array()->empty())
    top.fail("target", "give one or more [[target]] tables (name, quantity, test, value)");
  for (std::size_t i = 0; i < targets->as_array()->size(); ++i) {
    TomlSection sec(*targets->as_array()->get(i)->as_table(), fmt::format("target[{}]", i),
                    top.file());
    CalibrationTarget t = read_target(sec, plan.tests);
    for (const CalibrationTarget& u : plan.targets)
      if (u.name == t.name) sec.fail("name", fmt::format("two targets are named '{}'", t.name));
    sec.finish();
    plan.targets.push_back(std::move(t));
  }
}

// Each parameter's `scales`: the targets it scales, by index.
void link_scales(CalibrationPlan& plan, const std::vector<std::vector<std::string>>& scale_names,
                 const toml::array& parameter_list, const std::string& file) {
  for (std::size_t i = 0; i < plan.parameters.size(); ++i)
    for (const std::string& s : scale_names[i]) {
      const auto it = std::find_if(plan.targets.begin(), plan.targets.end(),
                                   [&](const CalibrationTarget& t) { return t.name == s; });
      if (it == plan.targets.end()) {
        TomlSection sec(*parameter_list[i].as_table(), fmt::format("parameter[{}]", i), file);
        sec.fail("scales", fmt::format("no [[target]] is named '{}'", s));
      }
      plan.parameters[i].scales.push_back(static_cast<std::size_t>(it - plan.targets.begin()));
    }
}

}  // namespace

std::vector<Override> run_overrides(const CalibrationPlan& plan, std::size_t test,
                                    std::uint64_t seed, const std::vector<double>& values) {
  std::vector<Override> out = plan.tests[test].overrides;
  out.push_back({"seed", std::to_string(seed), plan.file.string() + ": seeds"});
  for (std::size_t i = 0; i < plan.parameters.size(); ++i)
    if (plan.parameters[i].model_key)
      out.push_back({plan.parameters[i].name, value_text(values[i]), plan.parameters[i].origin});
  for (const Tie& tie : plan.ties) {
    double v = tie.constant;
    for (const std::size_t p : tie.times) v *= values[p];
    for (const std::size_t p : tie.divided_by) v /= values[p];
    out.push_back({tie.key, value_text(v), tie.origin});
  }
  return out;
}

std::string HistoryPoint::key() const {
  return column == "stage" ? "stage=" + stage : fmt::format("{}={:.17g}", column, value);
}

std::string RunQuantity::key() const {
  if (!history) return name;
  const std::string text = fmt::format("history.{}@{}", name, at.key());
  return from.column.empty() ? text : text + " from " + from.key();
}

CalibrationPlan read_calibration_file(const std::filesystem::path& file) {
  const toml::table root = parse_toml_file(file);
  const std::string name = file.string();
  CalibrationPlan plan;
  // The same file however it is spelled (relative, absolute, through "./"): its runs replay.
  plan.file = std::filesystem::absolute(file).lexically_normal();
  TomlSection top(root, "", name);
  read_title_and_output(top, file, plan.title, plan.output);
  plan.seeds = read_seeds(top);
  plan.step = top.number("step", 0.1);
  if (!(plan.step > 0 && plan.step < 1))
    top.fail("step", "the sensitivity step is a fraction of the value in (0, 1)");
  plan.linearised_steps = static_cast<int>(top.integer("linearised_steps", 8, 0, 100));
  plan.secant_update = top.boolean("secant_update", true);
  read_budget(top.sub("budget"), plan);
  plan.tests = read_tests(top, file);
  std::vector<std::vector<std::string>> scale_names;
  const toml::array& parameter_list = read_parameters(top, plan, scale_names);
  read_ties(top, plan);
  read_targets(top, plan);
  link_scales(plan, scale_names, parameter_list, name);
  top.finish();
  const long per_evaluation = static_cast<long>(plan.tests.size() * plan.seeds.size());
  if (plan.max_runs < per_evaluation)
    top.fail_at(root.at_path("budget.runs").node(), "budget.runs",
                fmt::format("{} runs cannot afford one evaluation ({} tests x {} seeds)",
                            plan.max_runs, plan.tests.size(), plan.seeds.size()));
  check_bounds(plan, parameter_list, name);
  return plan;
}

}  // namespace vorodec::workflows
