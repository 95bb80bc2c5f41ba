#include "override.hpp"

#include <fmt/format.h>

#include <charconv>
#include <vector>

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

}  // namespace vorodec::io
