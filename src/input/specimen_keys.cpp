// [specimen] (Voronoi, prepared or grain-based), the [[mineral]] tables and [blocks].
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "sections.hpp"
#include "vorodec/io/grain_file.hpp"

namespace vorodec::io {

namespace {

// A length of the specimen (m): within [kMinLength, kMaxLength], so that areas, block counts and
// the tessellation's tolerances stay in double range.
double specimen_length(TomlSection& sec, std::string_view key) {
  const double v = sec.positive(key, laws::required);
  if (v < kMinLength || v > kMaxLength)
    sec.fail(key, fmt::format("must be between {:g} m and {:g} m (got {:g} m)", kMinLength,
                              kMaxLength, v));
  return v;
}

// The file `key` names (relative to the model file), which must exist; `what` names it in errors.
std::filesystem::path existing_file(TomlSection& sec, std::string_view key, std::string_view what,
                                    const ModelConfig& cfg) {
  std::filesystem::path p = sec.string(key, nullptr);
  if (p.is_relative()) p = cfg.file.parent_path() / p;
  if (!file_exists(p)) sec.fail(key, fmt::format("{} '{}' does not exist", what, p.string()));
  return p;
}

void read_outline(TomlSection& sec, geometry::Outline& outline) {
  const std::string rect = "rectangle";
  const std::string shape = sec.string("shape", &rect);
  if (shape == "rectangle") {
    outline.kind = geometry::OutlineKind::rectangle;
    outline.width = specimen_length(sec, "width");
    outline.height = specimen_length(sec, "height");
  } else if (shape == "disc") {
    outline.kind = geometry::OutlineKind::disc;
    outline.diameter = specimen_length(sec, "diameter");
    // A flattened Brazilian disc: flats that spread the platens' load over an arc.
    const double flat = sec.non_negative("flat_angle", 0.0);
    if (flat > 60.0) sec.fail("flat_angle", fmt::format("must be at most 60 deg (got {:g})", flat));
    outline.flat_angle = flat * std::numbers::pi / 180.0;
  } else {
    sec.fail("shape", fmt::format("must be \"rectangle\" or \"disc\" (got \"{}\")", shape));
  }
}

std::vector<Mineral> read_minerals(TomlSection& top, bool need_fractions) {
  const toml::node* n = top.node("mineral");
  if (!n || !n->is_array_of_tables())
    top.fail("mineral",
             "a grain-based specimen needs [[mineral]] tables (name, fraction, density)");
  std::vector<Mineral> minerals;
  double sum = 0;
  const toml::array& list = *n->as_array();
  for (std::size_t i = 0; i < list.size(); ++i) {
    TomlSection m(*list[i].as_table(), fmt::format("mineral[{}]", i), top.file());
    Mineral x;
    x.name = m.string("name", nullptr);
    for (const Mineral& y : minerals)
      if (y.name == x.name) m.fail("name", fmt::format("mineral '{}' is given twice", x.name));
    x.fraction =
        need_fractions || m.has("fraction") ? m.non_negative("fraction", laws::required) : 0.0;
    if (x.fraction > 1) m.fail("fraction", "must be an area fraction between 0 and 1");
    x.density = m.positive("density", laws::required);
    if (m.has("E")) x.youngs_modulus = m.positive("E", laws::required);
    if (m.has("nu")) {
      x.poisson_ratio = m.number("nu", laws::required);
      if (!(x.poisson_ratio > -1.0 && x.poisson_ratio < 0.5))
        m.fail("nu", fmt::format("must be > -1 and < 0.5 (got {})", x.poisson_ratio));
    }
    if (m.has("E") != m.has("nu"))
      m.fail(m.has("E") ? "E" : "nu", "give both E and nu, or neither");
    m.finish();
    sum += x.fraction;
    minerals.push_back(x);
  }
  if (need_fractions && std::abs(sum - 1) > 1e-3)
    top.fail_at(n, "mineral",
                fmt::format("the minerals' fractions sum to {:.6g} (must be 1)", sum));
  return minerals;
}

void read_grain_specimen(TomlSection& sec, TomlSection& top, ModelConfig& cfg) {
  GrainConfig g;
  auto& t = cfg.tessellation;
  if (sec.has("grain_file")) {
    g.grain_file = existing_file(sec, "grain_file", "grain file", cfg);
  } else {
    read_outline(sec, t.outline);
    g.settings.grain_size = specimen_length(sec, "grain_size");
  }
  const std::string voronoi = "voronoi";
  const std::string sub = sec.string("sub_blocks", &voronoi);
  if (sub == "trigon")
    g.settings.sub_blocks = geometry::SubBlocks::trigon;
  else if (sub != "voronoi")
    sec.fail("sub_blocks", fmt::format("must be \"voronoi\" or \"trigon\" (got \"{}\")", sub));
  g.settings.sub_block_size = specimen_length(sec, "sub_block_size");
  if (g.settings.grain_size > 0 && g.settings.sub_block_size > g.settings.grain_size)
    sec.fail("sub_block_size", "must not be larger than grain_size");
  g.settings.sub_block_lloyd_iterations =
      static_cast<int>(sec.integer("sub_block_lloyd_iterations", 3, 0, kMaxLloydIterations));
  t.lloyd_iterations = static_cast<int>(sec.integer("lloyd_iterations", 0, 0, kMaxLloydIterations));
  t.min_edge_length = sec.non_negative("min_edge_length", 0.0);
  sec.finish();
  g.minerals = read_minerals(top, !g.grain_file);
  std::vector<std::string> names;
  for (const Mineral& m : g.minerals) {
    g.settings.fractions.push_back(m.fraction);
    names.push_back(m.name);
    cfg.density += m.fraction * m.density;
  }
  if (g.grain_file) {
    g.settings.grains = read_grain_file(*g.grain_file, names);
    cfg.density = g.minerals.front().density;  // platens only: their mass never enters
  }
  cfg.grains = std::move(g);
}

void read_specimen(TomlSection sec, TomlSection& top, ModelConfig& cfg) {
  cfg.specimen_line = sec.line();
  const std::string voronoi = "voronoi";
  const std::string kind = sec.string("kind", &voronoi);
  if (kind == "grains") return read_grain_specimen(sec, top, cfg);
  if (kind != "voronoi")
    sec.fail("kind", fmt::format("must be \"voronoi\" or \"grains\" (got \"{}\")", kind));
  if (sec.has("file")) {
    cfg.specimen_file = existing_file(sec, "file", "specimen file", cfg);
    sec.finish();  // a prepared specimen carries its own geometry: no other keys allowed
    return;
  }
  auto& t = cfg.tessellation;
  read_outline(sec, t.outline);
  if (sec.has("block_count") == sec.has("mean_edge_length"))
    sec.fail("block_count", "give exactly one of 'block_count' and 'mean_edge_length'");
  t.block_count = static_cast<int>(sec.integer("block_count", 0, 2, static_cast<long>(kMaxBlocks)));
  t.mean_edge_length = sec.has("mean_edge_length") ? specimen_length(sec, "mean_edge_length") : 0.0;
  t.lloyd_iterations = static_cast<int>(sec.integer("lloyd_iterations", 0, 0, kMaxLloydIterations));
  t.min_edge_length = sec.non_negative("min_edge_length", 0.0);
  sec.finish();
}

// A grain-based specimen's [blocks]: only the zoning (density and elasticity are the minerals').
void read_grain_blocks(TomlSection blocks, const GrainConfig& g, DeformableSettings& d) {
  for (const char* key : {"density", "E", "nu"})
    if (blocks.has(key))
      blocks.fail(key, "a grain-based specimen takes density, E and nu from each [[mineral]]");
  d.enabled = blocks.boolean("deformable", false);
  if (d.enabled) {
    d.zone_size = blocks.positive("zone_size", laws::required);
    for (const Mineral& m : g.minerals)
      if (m.youngs_modulus == 0)
        blocks.fail("deformable", fmt::format("deformable grains need E and nu in every "
                                              "[[mineral]]; '{}' has none",
                                              m.name));
  }
  blocks.finish();
}

void read_voronoi_blocks(TomlSection blocks, ModelConfig& cfg) {
  cfg.density = blocks.positive("density", laws::required);
  cfg.deformable.enabled = blocks.boolean("deformable", false);
  if (cfg.deformable.enabled) {
    cfg.deformable.zone_size = blocks.positive("zone_size", laws::required);
    cfg.deformable.youngs_modulus = blocks.positive("E", laws::required);
    cfg.deformable.poisson_ratio = blocks.number("nu", laws::required);
    if (!(cfg.deformable.poisson_ratio > -1.0 && cfg.deformable.poisson_ratio < 0.5))
      blocks.fail("nu",
                  fmt::format("must be > -1 and < 0.5 (got {})", cfg.deformable.poisson_ratio));
  }
  blocks.finish();
}

}  // namespace

void read_specimen_table(TomlSection& top, ModelConfig& cfg) {
  read_specimen(top.sub("specimen"), top, cfg);
}

void read_blocks_table(TomlSection& top, ModelConfig& cfg) {
  if (!cfg.grains) return read_voronoi_blocks(top.sub("blocks"), cfg);
  if (top.has("blocks")) read_grain_blocks(top.sub("blocks"), *cfg.grains, cfg.deformable);
}

}  // namespace vorodec::io
