#include "vorodec/workflows/batch_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

#include "plan_keys.hpp"
#include "vorodec/input/override.hpp"
#include "vorodec/input/toml_section.hpp"

namespace vorodec::workflows {

// The model-file reader's tools: a batch file is read as model files are.
using namespace vorodec::io;

namespace {

std::filesystem::path read_model(TomlSection& sec, const std::filesystem::path& batch_file) {
  std::filesystem::path p = sec.string("model", nullptr);
  if (p.is_relative()) p = (batch_file.parent_path() / p).lexically_normal();
  if (!std::filesystem::is_regular_file(p))
    sec.fail("model", fmt::format("model file '{}' does not exist", p.string()));
  return p;
}

// Folder names: letters, digits and . _ - = + only.
std::string folder_name(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) &&
        std::string_view("._-=+").find(c) == std::string_view::npos)
      c = '_';
  return s;
}

std::string label(const toml::node& v) {
  if (const auto d = v.value_exact<double>()) return fmt::format("{:g}", *d);
  if (const auto s = v.value_exact<std::string>()) return *s;
  return toml_text(v);
}

struct GridAxis {
  std::string key;
  const toml::array* values;
};

// The base cases: the [[case]] tables, each with the top-level `set` first, or the one model.
std::vector<BatchCase> read_cases(TomlSection& top, const std::filesystem::path& file) {
  std::vector<BatchCase> bases;
  const std::vector<Override> common = read_set(top);
  const bool has_model = top.has("model");
  const std::filesystem::path model = has_model ? read_model(top, file) : std::filesystem::path();

  if (const toml::node* cases = top.node("case")) {
    if (!cases->is_array_of_tables())
      top.fail("case", "must be [[case]] tables (name, model, set)");
    const toml::array& list = *cases->as_array();
    for (std::size_t i = 0; i < list.size(); ++i) {
      TomlSection sec(*list[i].as_table(), fmt::format("case[{}]", i), top.file());
      BatchCase c;
      c.model = sec.has("model") || !has_model ? read_model(sec, file) : model;
      const std::string stem = c.model.stem().string();
      c.name = folder_name(sec.string("name", &stem));
      c.overrides = common;
      for (Override& o : read_set(sec)) c.overrides.push_back(std::move(o));
      sec.finish();
      bases.push_back(std::move(c));
    }
  } else {
    if (!has_model) top.fail("model", "give a model file, or [[case]] tables each with a model");
    bases.push_back({model.stem().string(), model, common});
  }
  return bases;
}

// [grid]: "key" = [values], in the table's (alphabetical) order.
std::vector<GridAxis> read_grid(TomlSection& top) {
  std::vector<GridAxis> grid;
  if (const toml::node* g = top.node("grid")) {
    if (!g->is_table()) top.fail("grid", "must be a table of \"key\" = [values]");
    TomlSection sec(*g->as_table(), "grid", top.file());
    for (const auto& [k, v] : *g->as_table()) {
      const toml::array* a = v.as_array();
      if (!a || a->empty()) sec.fail(k.str(), "must be a non-empty array of values");
      sec.node(k.str());
      grid.push_back({std::string(k.str()), a});
    }
  }
  return grid;
}

// Every base case times every grid combination; the last grid key (alphabetically) varies
// fastest.
std::vector<BatchCase> expand(const std::vector<BatchCase>& bases,
                              const std::vector<GridAxis>& grid, const std::string& name) {
  std::vector<BatchCase> cases;
  std::size_t combinations = 1;
  for (const GridAxis& a : grid) combinations *= a.values->size();
  for (const BatchCase& base : bases) {
    for (std::size_t n = 0; n < combinations; ++n) {
      BatchCase c = base;
      std::size_t rest = n;
      std::string suffix;
      for (auto a = grid.rbegin(); a != grid.rend(); ++a) {
        const toml::node& v = *a->values->get(rest % a->values->size());
        rest /= a->values->size();
        c.overrides.push_back(
            {a->key, toml_text(v), fmt::format("{}:{}", name, v.source().begin.line)});
        const std::string leaf = a->key.substr(a->key.find_last_of('.') + 1);
        suffix = fmt::format("_{}={}", leaf.substr(0, leaf.find('[')), label(v)) + suffix;
      }
      // Grid overrides were pushed last-key-first; restore the grid's (alphabetical) order.
      std::reverse(c.overrides.end() - static_cast<long>(grid.size()), c.overrides.end());
      c.name = folder_name(c.name + suffix);
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

}  // namespace

std::string override_value(const BatchCase& c, const std::string& key) {
  std::string value;
  for (const Override& o : c.overrides)
    if (o.key == key) value = o.value;  // the last one wins, as when applied
  return value;
}

BatchPlan read_batch_file(const std::filesystem::path& file) {
  const toml::table root = parse_toml_file(file);
  const std::string name = file.string();
  BatchPlan plan;
  plan.file = file;
  TomlSection top(root, "", name);
  read_title_and_output(top, file, plan.title, plan.output);
  const std::vector<BatchCase> bases = read_cases(top, file);
  const std::vector<GridAxis> grid = read_grid(top);
  top.finish();
  plan.cases = expand(bases, grid, name);

  std::set<std::string> names;
  for (std::size_t i = 0; i < plan.cases.size(); ++i)
    if (!names.insert(plan.cases[i].name).second)
      top.fail("case", fmt::format("two cases are named '{}': give each [[case]] its own name",
                                   plan.cases[i].name));
  for (const BatchCase& c : plan.cases)
    for (const Override& o : c.overrides)
      if (std::find(plan.columns.begin(), plan.columns.end(), o.key) == plan.columns.end())
        plan.columns.push_back(o.key);
  return plan;
}

}  // namespace vorodec::workflows
