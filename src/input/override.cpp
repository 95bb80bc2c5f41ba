#include "vorodec/input/override.hpp"

#include <fmt/format.h>

#include <charconv>
#include <sstream>
#include <vector>

#include "vorodec/input/toml_section.hpp"

namespace vorodec::io {

namespace {

struct Segment {
  std::string key;
  long index = -1;  // "stage[1]" -> index 1
};

std::vector<Segment> split(const Override& o, const std::string& file) {
  std::vector<Segment> out;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t dot = o.key.find('.', begin);
    const std::string part = o.key.substr(begin, dot == std::string::npos ? dot : dot - begin);
    Segment s{part, -1};
    if (const auto open = part.find('['); open != std::string::npos) {
      s.key = part.substr(0, open);
      const char* first = part.data() + open + 1;
      const char* last = part.data() + part.size() - 1;
      const auto [end, ec] = std::from_chars(first, last, s.index);
      if (part.back() != ']' || ec != std::errc() || end != last || s.index < 0)
        fail_override(o, file, fmt::format("'{}': an index is written [0], [1], ...", part));
    }
    if (s.key.empty()) fail_override(o, file, "empty key (keys are written a.b.c or a[0].b)");
    out.push_back(s);
    if (dot == std::string::npos) return out;
    begin = dot + 1;
  }
}

toml::node* element(toml::node* n, const Segment& s, const Override& o, const std::string& file) {
  toml::array* a = n->as_array();
  if (!a) fail_override(o, file, fmt::format("'{}' is not an array", s.key));
  if (static_cast<std::size_t>(s.index) >= a->size())
    fail_override(o, file, fmt::format("'{}' has {} entries", s.key, a->size()));
  return a->get(static_cast<std::size_t>(s.index));
}

}  // namespace

void fail_override(const Override& o, const std::string& file, const std::string& message) {
  throw ModelFileError(fmt::format("{}: override '{}' of {}: {}", o.origin, o.key, file, message),
                       o.key, message);
}

bool concerns(const std::string& error_key, const std::string& override_key) {
  const auto inside = [](const std::string& a, const std::string& b) {
    return a.size() > b.size() && a.compare(0, b.size(), b) == 0 &&
           (a[b.size()] == '.' || a[b.size()] == '[');
  };
  return error_key == override_key || inside(error_key, override_key) ||
         inside(override_key, error_key);
}

void apply_override(toml::table& root, const Override& o, const std::string& file) {
  const std::vector<Segment> path = split(o, file);
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + o.value);
  } catch (const toml::parse_error&) {  // a bare word on the command line: a string
    parsed.insert("value", o.value);
  }
  toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Segment& s = path[i];
    toml::node* n = t->get(s.key);
    if (!n) {
      if (s.index >= 0) fail_override(o, file, fmt::format("the model has no '{}'", s.key));
      n = &t->insert(s.key, toml::table{}).first->second;
    }
    if (s.index >= 0) n = element(n, s, o, file);
    t = n->as_table();
    if (!t) fail_override(o, file, fmt::format("'{}' is a value, not a table", s.key));
  }
  const Segment& last = path.back();
  toml::node& value = *parsed.get("value");
  if (last.index < 0) {
    t->insert_or_assign(last.key, std::move(value));
    return;
  }
  toml::node* n = t->get(last.key);
  if (!n) fail_override(o, file, fmt::format("the model has no '{}'", last.key));
  element(n, last, o, file);
  toml::array& a = *n->as_array();
  a.replace(a.cbegin() + last.index, std::move(value));
}

std::string toml_text(const toml::node& n) {
  if (const auto d = n.value_exact<double>()) {
    std::string t = fmt::format("{}", *d);
    if (t.find_first_of(".en") == std::string::npos) t += ".0";
    return t;
  }
  std::ostringstream s;
  n.visit([&](const auto& v) { s << v; });
  return s.str();
}

namespace {

std::string origin(const std::string& file, const toml::node& n) {
  return fmt::format("{}:{}", file, n.source().begin.line);
}

// A [set] table: "a.b" = v and a.b = v (nested tables) both set key a.b.
void flatten(const toml::table& t, const std::string& prefix, const std::string& file,
             std::vector<Override>& out) {
  for (const auto& [k, v] : t) {
    const std::string key =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const toml::table* sub = v.as_table())
      flatten(*sub, key, file, out);
    else
      out.push_back({key, toml_text(v), origin(file, v)});
  }
}

}  // namespace

std::vector<Override> read_set(TomlSection& sec) {
  std::vector<Override> out;
  if (const toml::node* n = sec.node("set")) {
    if (!n->is_table()) sec.fail("set", "must be a table of \"key\" = value overrides");
    flatten(*n->as_table(), "", sec.file(), out);
  }
  return out;
}

}  // namespace vorodec::io
