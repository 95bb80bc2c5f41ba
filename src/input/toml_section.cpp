#include "vorodec/input/toml_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vorodec::io {

toml::table parse_toml_file(const std::filesystem::path& file) {
  try {
    return toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw ModelFileError(fmt::format("{}:{}:{}: {}", file.string(), e.source().begin.line,
                                     e.source().begin.column, e.description()));
  } catch (const std::exception& e) {
    throw ModelFileError(fmt::format("{}: cannot read: {}", file.string(), e.what()));
  }
}

namespace {
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}
}  // namespace

TomlSection::TomlSection(const toml::table& table, std::string path, std::string file,
                         const toml::table* inherited)
    : table_(table), inherited_(inherited), path_(std::move(path)), file_(std::move(file)) {}

const toml::node* TomlSection::find(std::string_view key) const {
  const toml::node* n = table_.get(key);
  return n || !inherited_ ? n : inherited_->get(key);
}

std::string TomlSection::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void TomlSection::fail(std::string_view key, const std::string& message) const {
  fail_at(find(key), key, message);
}

void TomlSection::fail_at(const toml::node* where, std::string_view key,
                          const std::string& message) const {
  const toml::source_region& at = where ? where->source() : table_.source();
  // Keys inherited from a base model file are reported against that file.
  const std::string& file = at.path ? *at.path : file_;
  throw ModelFileError(
      fmt::format("{}:{}: key '{}': {}", file, at.begin.line, key_path(key), message),
      key_path(key), message);
}

const toml::node* TomlSection::node(std::string_view key) {
  used_.insert(std::string(key));
  return find(key);
}

double TomlSection::number(std::string_view key, double fallback) {
  const toml::node* n = node(key);
  if (!n) {
    if (std::isnan(fallback)) fail(key, "required key is missing");
    return fallback;
  }
  const auto v = n->value<double>();
  if (!v || !n->is_number()) fail(key, "must be a number");
  if (!std::isfinite(*v)) fail(key, "must be finite");
  return *v;
}

double TomlSection::positive(std::string_view key, double fallback) {
  const double v = number(key, fallback);
  if (!(v > 0)) fail(key, fmt::format("must be > 0 (got {})", v));
  return v;
}

double TomlSection::non_negative(std::string_view key, double fallback) {
  const double v = number(key, fallback);
  if (!(v >= 0)) fail(key, fmt::format("must be >= 0 (got {})", v));
  return v;
}

long TomlSection::integer(std::string_view key, long fallback, long min, long max) {
  const toml::node* n = node(key);
  if (!n) return fallback;
  const auto v = n->value_exact<std::int64_t>();
  if (!v) fail(key, "must be an integer");
  if (*v < min) fail(key, fmt::format("must be >= {} (got {})", min, *v));
  if (*v > max) fail(key, fmt::format("must be <= {} (got {})", max, *v));
  return static_cast<long>(*v);
}

std::string TomlSection::string(std::string_view key, const std::string* fallback) {
  const toml::node* n = node(key);
  if (!n) {
    if (!fallback) fail(key, "required key is missing");
    return *fallback;
  }
  const auto v = n->value_exact<std::string>();
  if (!v) fail(key, "must be a string");
  return *v;
}

bool TomlSection::boolean(std::string_view key, bool fallback) {
  const toml::node* n = node(key);
  if (!n) return fallback;
  const auto v = n->value_exact<bool>();
  if (!v) fail(key, "must be true or false");
  return *v;
}

std::vector<double> TomlSection::numbers(std::string_view key) {
  const toml::node* n = node(key);
  if (!n) fail(key, "required key is missing");
  const toml::array* a = n->as_array();
  if (!a || a->empty()) fail(key, "must be a non-empty array of numbers");
  std::vector<double> out;
  for (const toml::node& e : *a) {
    const auto v = e.value<double>();
    if (!e.is_number() || !v || !std::isfinite(*v))
      fail_at(&e, key, "must hold finite numbers only");
    out.push_back(*v);
  }
  return out;
}

TomlSection TomlSection::sub(std::string_view key) {
  const toml::node* n = node(key);
  if (!n) fail(key, "required table is missing");
  if (!n->is_table()) fail(key, "must be a table");
  return TomlSection(*n->as_table(), key_path(key), file_);
}

void TomlSection::finish() const {
  for (const toml::table* t : {&table_, inherited_}) {
    if (!t) continue;
    for (const auto& [k, v] : *t) {
      if (used_.count(k.str())) continue;
      std::string hint;
      std::size_t best = 3;
      for (const auto& u : used_) {
        const std::size_t d = edit_distance(k.str(), u);
        if (d < best) {
          best = d;
          hint = fmt::format(" (did you mean '{}'?)", u);
        }
      }
      const std::string reason = "unknown key" + hint;
      const std::string& file = k.source().path ? *k.source().path : file_;
      throw ModelFileError(fmt::format("{}:{}: key '{}': {}", file, k.source().begin.line,
                                       key_path(k.str()), reason),
                           key_path(k.str()), reason);
    }
  }
}

}  // namespace vorodec::io
