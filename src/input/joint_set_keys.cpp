// [[joint_set]]: joint sets by their statistics, or fractures from a CSV file, each with a law.
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <string_view>

#include "sections.hpp"
#include "vorodec/io/csv_fields.hpp"

namespace vorodec::io {

namespace {

constexpr double kMaxJoints = 1e5;  // joint lines of one set across the specimen

// The outline's bounding box: fractures must reach into it.
geometry::Point box_size(const geometry::Outline& o) {
  if (o.kind == geometry::OutlineKind::disc) return {o.diameter, o.diameter};
  return {o.width, o.height};
}

bool outside_box(geometry::Point a, geometry::Point b, geometry::Point size) {
  return std::max(a.x, b.x) < 0 || std::min(a.x, b.x) > size.x || std::max(a.y, b.y) < 0 ||
         std::min(a.y, b.y) > size.y;
}

// A fracture file: a header "x1,y1,x2,y2" (m) with an optional fifth column "set" naming the
// [[joint_set]] of each row (default: the set whose table names the file).
void read_fracture_file(const std::filesystem::path& file, std::int32_t own_set,
                        const std::vector<std::string>& names, geometry::Point size,
                        std::vector<ModelConfig::JointSet>& sets) {
  std::ifstream in(file);
  if (!in) throw ModelFileError(fmt::format("{}: cannot open fracture file", file.string()));
  const auto fail = [&](int line, const std::string& what) {
    throw ModelFileError(fmt::format("{}:{}: {}", file.string(), line, what));
  };
  std::string text;
  int line = 0;
  bool with_set = false, header = false;
  std::size_t rows = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::string_view t = trim(text);
    if (t.empty() || t.front() == '#') continue;
    const auto f = split_fields(t);
    if (!header) {
      header = true;
      with_set = f.size() == 5 && f[4] == "set";
      if (f.size() < 4 || f[0] != "x1" || f[1] != "y1" || f[2] != "x2" || f[3] != "y2" ||
          (f.size() == 5 && !with_set) || f.size() > 5)
        fail(line, "the header must be 'x1,y1,x2,y2' or 'x1,y1,x2,y2,set'");
      continue;
    }
    if (f.size() != (with_set ? 5u : 4u))
      fail(line, fmt::format("expected {} fields, got {}", with_set ? 5 : 4, f.size()));
    double v[4];
    for (int k = 0; k < 4; ++k)
      if (!parse_double(f[static_cast<std::size_t>(k)], v[k]))
        fail(line, fmt::format("field {} ('{}') is not a finite number (m)", k + 1,
                               f[static_cast<std::size_t>(k)]));
    const geometry::Point a{v[0], v[1]}, b{v[2], v[3]};
    if (std::hypot(b.x - a.x, b.y - a.y) <= 0) fail(line, "the fracture has zero length");
    if (outside_box(a, b, size))
      fail(line, fmt::format("the fracture lies outside the specimen (0..{:g} m x 0..{:g} m)",
                             size.x, size.y));
    std::int32_t set = own_set;
    if (with_set) {
      set = -1;
      for (std::size_t k = 0; k < names.size(); ++k)
        if (names[k] == f[4]) set = static_cast<std::int32_t>(k);
      if (set < 0) fail(line, fmt::format("no [[joint_set]] is named '{}'", f[4]));
    }
    sets[static_cast<std::size_t>(set)].fractures.push_back({a, b, set});
    ++rows;
  }
  if (rows == 0) fail(line, "the fracture file has no fractures");
}

geometry::JointSetGeometry read_statistics(TomlSection& sec, const ModelConfig& cfg) {
  geometry::JointSetGeometry g;
  g.dip_deg = sec.number("dip", laws::required);
  if (!(g.dip_deg >= -180 && g.dip_deg <= 180))
    sec.fail("dip", fmt::format("must be between -180 and 180 deg (got {:g})", g.dip_deg));
  g.spacing = sec.positive("spacing", laws::required);
  const geometry::Point size = box_size(cfg.tessellation.outline);
  if (std::hypot(size.x, size.y) / g.spacing > kMaxJoints)
    sec.fail("spacing", fmt::format("gives more than {:g} joints across the specimen (spacing "
                                    "{:g} m)",
                                    kMaxJoints, g.spacing));
  g.trace = sec.non_negative("trace", 0.0);
  if (g.trace > 0) {
    g.gap = sec.positive("gap", laws::required);
  } else if (sec.has("gap")) {
    sec.fail("gap", "a gap needs a trace length (without 'trace' the joints are persistent)");
  }
  g.origin = {0.5 * size.x, 0.5 * size.y};
  if (sec.has("origin")) {
    const std::vector<double> o = sec.numbers("origin");
    if (o.size() != 2) sec.fail("origin", "must be [x, y] (m)");
    g.origin = {o[0], o[1]};
    if (!(g.origin.x >= 0 && g.origin.x <= size.x && g.origin.y >= 0 && g.origin.y <= size.y))
      sec.fail("origin", fmt::format("must lie in the specimen's bounding box (0..{:g} m x 0..{:g} "
                                     "m)",
                                     size.x, size.y));
  }
  g.dip_spread = sec.non_negative("dip_spread", 0.0);
  g.spacing_spread = sec.non_negative("spacing_spread", 0.0);
  return g;
}

}  // namespace

void read_joint_set_tables(TomlSection& top, ModelConfig& cfg) {
  const toml::node* n = top.node("joint_set");
  if (!n) return;
  if (!n->is_array_of_tables()) top.fail("joint_set", "must be [[joint_set]] tables");
  if (cfg.grains || cfg.specimen_file)
    top.fail("joint_set",
             "joint sets cut a Voronoi specimen built from [specimen] (not grains "
             "or a prepared specimen file)");
  const toml::array& list = *n->as_array();
  std::vector<TomlSection> tables;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    tables.emplace_back(*list[i].as_table(), fmt::format("joint_set[{}]", i), top.file());
    const std::string fallback = fmt::format("set{}", i + 1);
    names.push_back(tables.back().string("name", &fallback));
    for (std::size_t k = 0; k < i; ++k)
      if (names[k] == names[i])
        tables.back().fail("name", fmt::format("joint set '{}' is given twice", names[i]));
  }
  cfg.joint_sets.resize(list.size());
  const geometry::Point size = box_size(cfg.tessellation.outline);
  for (std::size_t i = 0; i < list.size(); ++i) {
    TomlSection& sec = tables[i];
    auto& set = cfg.joint_sets[i];
    set.name = names[i];
    if (sec.has("file") && sec.has("dip"))
      sec.fail("file", "give a fracture file or the set's statistics (dip, spacing), not both");
    if (sec.has("file")) {
      std::filesystem::path p = sec.string("file", nullptr);
      if (p.is_relative()) p = cfg.file.parent_path() / p;
      if (!file_exists(p))
        sec.fail("file", fmt::format("fracture file '{}' does not exist", p.string()));
      cfg.sources.push_back(p);
      read_fracture_file(p, static_cast<std::int32_t>(i), names, size, cfg.joint_sets);
    } else if (sec.has("dip") || sec.has("spacing")) {
      set.statistics = read_statistics(sec, cfg);
    }
    set.law = read_law(sec, "mohr_coulomb");
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!cfg.joint_sets[i].statistics && cfg.joint_sets[i].fractures.empty() &&
        !tables[i].has("file"))
      tables[i].fail("dip",
                     "a joint set needs 'dip' and 'spacing', or a fracture 'file' (or "
                     "rows of another set's file that name it)");
    tables[i].finish();
  }
}

}  // namespace vorodec::io
