// The lengths of a specimen against one another, before it is tessellated: the block count
// (estimated from the outline area) stays bounded, the outline holds its blocks, and blocks are
// longer than the edges collapsed (min_edge_length) and the corners rounded (rounding_length).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sections.hpp"

namespace vorodec::io {

namespace {

std::string mm(double metres) {
  return fmt::format("{:.4g} mm", metres * 1e3);
}

double circle(double diameter) {
  return std::numbers::pi / 4 * diameter * diameter;
}

// A length the specimen's blocks must exceed, and what it is, for messages.
struct Bound {
  double length;
  std::string what;
};

// The specimen's outline: its sides, area and shorter side, and the key that sets that side.
struct Extent {
  double width, height, area, smallest;
  std::string narrow_key;
};

// A grain file's outline is the grains' bounding box; each side within [kMinLength, kMaxLength].
void grain_file_box(TomlSection& spec, const GrainConfig& g, Extent& e) {
  geometry::Point lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  geometry::Point hi{-lo.x, -lo.y};
  for (const geometry::Grain& grain : g.settings.grains)
    for (const geometry::Point p : grain.corners) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
  e.width = hi.x - lo.x;
  e.height = hi.y - lo.y;
  e.narrow_key = "grain_file";
  for (const double v : {e.width, e.height})
    if (!(v >= kMinLength && v <= kMaxLength))
      spec.fail("grain_file", fmt::format("the grains span {:g} x {:g} m: each side must be "
                                          "between {:g} m and {:g} m",
                                          e.width, e.height, kMinLength, kMaxLength));
}

Extent outline_extent(TomlSection& spec, const ModelConfig& cfg) {
  const geometry::Outline& o = cfg.tessellation.outline;
  const bool disc = o.kind == geometry::OutlineKind::disc;
  Extent e{disc ? o.diameter : o.width, disc ? o.diameter : o.height, 0, 0,
           disc                  ? "diameter"
           : o.width <= o.height ? "width"
                                 : "height"};
  const bool grain_file = cfg.grains && cfg.grains->grain_file;
  if (grain_file) grain_file_box(spec, *cfg.grains, e);
  e.area = disc && !grain_file ? circle(o.diameter) : e.width * e.height;
  e.smallest = std::min(e.width, e.height);
  return e;
}

// A grain-based specimen's block: the sub-block, sqrt(pi/4) sub_block_size.
Bound grain_block(TomlSection& spec, const GrainConfig& g, const Extent& e) {
  const double s = g.settings.sub_block_size;
  if (!g.grain_file) {
    const double grain = g.settings.grain_size;
    const double grains = e.area / circle(grain);
    if (grains > kMaxBlocks)
      spec.fail("grain_size", fmt::format("gives about {:.3g} grains (outline area / (pi/4 "
                                          "grain_size^2)), more than the {:.0f} allowed",
                                          grains, kMaxBlocks));
    if (std::round(grains) < 2)
      spec.fail("grain_size", "is too large: fewer than 2 grains fit in the outline");
    if (!(kPoissonEdgeFactor * std::sqrt(circle(grain)) < e.smallest))
      spec.fail(e.narrow_key,
                fmt::format("({}) must be larger than the grains' mean edge, about "
                            "0.65 sqrt(pi/4) grain_size = {}",
                            mm(e.smallest), mm(kPoissonEdgeFactor * std::sqrt(circle(grain)))));
  }
  const double subs = e.area / circle(s);
  if (subs > kMaxBlocks)
    spec.fail("sub_block_size", fmt::format("gives about {:.3g} sub-blocks (outline area / "
                                            "(pi/4 sub_block_size^2)), more than the {:.0f} "
                                            "allowed",
                                            subs, kMaxBlocks));
  const double block = std::sqrt(circle(s));
  return {block, fmt::format("the sub-block size sqrt(pi/4) sub_block_size = {}", mm(block))};
}

// A Voronoi specimen's block: sqrt(area / block_count), or mean_edge_length / 0.65.
Bound voronoi_block(TomlSection& spec, const geometry::TessellationSettings& t, const Extent& e) {
  if (t.block_count > 0) {
    const double n = t.block_count;
    const double block = std::sqrt(e.area / n);
    Bound b{block, fmt::format("the block size sqrt(area / block_count) = {}", mm(block))};
    if (!(kPoissonEdgeFactor * block < e.smallest))
      spec.fail(e.narrow_key, fmt::format("({}) must be larger than the blocks' mean edge, about "
                                          "0.65 sqrt(area / block_count) = {}",
                                          mm(e.smallest), mm(kPoissonEdgeFactor * block)));
    return b;
  }
  const double edge = t.mean_edge_length;
  const double n = e.area * std::pow(kPoissonEdgeFactor / edge, 2);
  if (n > kMaxBlocks)
    spec.fail("mean_edge_length",
              fmt::format("gives about {:.3g} blocks (area x (0.65 / mean_edge_length)^2), more "
                          "than the {:.0f} allowed",
                          n, kMaxBlocks));
  if (!(edge < e.smallest))
    spec.fail("mean_edge_length",
              fmt::format("({}) must be smaller than the specimen ({})", mm(edge), mm(e.smallest)));
  if (std::round(n) < 2) spec.fail("mean_edge_length", "is too large: fewer than 2 blocks");
  const double block = edge / kPoissonEdgeFactor;
  return {block, fmt::format("the block size mean_edge_length / 0.65 = {}", mm(block))};
}

// The shortest length of the specimen: its block, its narrow side, its grains.
Bound shortest_length(const GrainConfig* g, const Extent& e, const Bound& block) {
  std::vector<Bound> lengths{
      block, {e.smallest, fmt::format("the specimen's {} ({})", e.narrow_key, mm(e.smallest))}};
  if (g && !g->grain_file)
    lengths.push_back(
        {g->settings.grain_size, fmt::format("grain_size ({})", mm(g->settings.grain_size))});
  return *std::min_element(lengths.begin(), lengths.end(),
                           [](const Bound& a, const Bound& b) { return a.length < b.length; });
}

// rounding_length and tolerance of [contact] against the specimen's lengths.
void check_contact(const toml::table& root, const ModelConfig& cfg, const Bound& shortest,
                   const Bound& block) {
  if (cfg.rounding_length > 0 || cfg.solver.contact_tolerance > 0) {
    TomlSection contact(*root.get("contact")->as_table(), "contact", cfg.file.string());
    if (!(2 * cfg.rounding_length < shortest.length))
      contact.fail("rounding_length", fmt::format("({}) must be shorter than half of {}",
                                                  mm(cfg.rounding_length), shortest.what));
    if (!(cfg.solver.contact_tolerance < block.length))
      contact.fail("tolerance", fmt::format("({}) must be shorter than {}",
                                            mm(cfg.solver.contact_tolerance), block.what));
  }
}

// The deformable blocks' zones and the damage grid's cells stay bounded.
void check_counts(const toml::table& root, const ModelConfig& cfg, double area) {
  const std::string file = cfg.file.string();
  if (cfg.deformable.enabled) {
    const double zones = 2 * area / std::pow(cfg.deformable.zone_size, 2);
    if (zones > kMaxZones)
      TomlSection(*root.get("blocks")->as_table(), "blocks", file)
          .fail("zone_size", fmt::format("gives about {:.3g} zones (2 x area / zone_size^2), more "
                                         "than the {:.0f} allowed",
                                         zones, kMaxZones));
  }
  if (cfg.output.damage_grid_cell > 0) {
    const double cells = area / std::pow(cfg.output.damage_grid_cell, 2);
    if (cells > kMaxDamageCells)
      TomlSection(*root.get("output")->as_table(), "output", file)
          .fail("damage_grid_cell",
                fmt::format("gives about {:.3g} cells (area / damage_grid_cell^2), more than the "
                            "{:.0f} allowed",
                            cells, kMaxDamageCells));
  }
}

}  // namespace

void check_lengths(const toml::table& root, const ModelConfig& cfg) {
  if (cfg.specimen_file) return;  // a prepared specimen: its blocks are given
  TomlSection spec(*root.get("specimen")->as_table(), "specimen", cfg.file.string());
  const Extent e = outline_extent(spec, cfg);
  const GrainConfig* g = cfg.grains ? &*cfg.grains : nullptr;
  const Bound block = g ? grain_block(spec, *g, e) : voronoi_block(spec, cfg.tessellation, e);
  // min_edge_length and 2 x rounding_length must be shorter than every length of the specimen.
  const Bound shortest = shortest_length(g, e, block);
  const double min_edge = cfg.tessellation.min_edge_length;
  if (!(min_edge < shortest.length))
    spec.fail("min_edge_length",
              fmt::format("({}) must be shorter than {}", mm(min_edge), shortest.what));
  check_contact(root, cfg, shortest, block);
  check_counts(root, cfg, e.area);
}

}  // namespace vorodec::io
