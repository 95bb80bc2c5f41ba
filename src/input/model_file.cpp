#include "vorodec/input/model_file.hpp"

#include <fmt/format.h>

#include "sections.hpp"
#include "vorodec/input/override.hpp"

namespace vorodec::io {

namespace {

// Tables merge key by key; any other value (arrays such as [[stage]] included) replaces. The
// nodes of `over` are moved, not copied: a copied toml++ node loses its file and line.
void merge_into(toml::table& base, toml::table&& over) {
  for (auto&& [key, node] : over) {
    toml::node* old = base.get(key.str());
    if (old && old->is_table() && node.is_table())
      merge_into(*old->as_table(), std::move(*node.as_table()));
    else
      base.insert_or_assign(key, std::move(node));
  }
}

// A model file may start from another: `base = "file.toml"` (relative to it). Keys it sets win.
toml::table load(const std::filesystem::path& file, int depth,
                 std::vector<std::filesystem::path>& sources, std::span<const DriverKeys> drivers) {
  toml::table t = parse_toml_file(file);
  sources.push_back(file);
  const toml::node* b = t.get("base");
  if (!b) return t;
  const auto name = b->value_exact<std::string>();
  const auto line = b->source().begin.line;
  if (!name)
    throw ModelFileError(fmt::format("{}:{}: key 'base': must be a string", file.string(), line));
  const std::filesystem::path path = file.parent_path() / *name;
  if (depth >= 8 || !file_exists(path))
    throw ModelFileError(fmt::format(
        "{}:{}: key 'base': {}", file.string(), line,
        depth >= 8 ? "more than 8 nested base files" : "no such file: " + path.string()));
  toml::table merged = load(path, depth + 1, sources, drivers);
  t.erase("base");
  // A load path replaces the base's: a driver's table (such as [shpb]) drops the base's [[stage]]s
  // and other drivers' tables, [[stage]]s drop its drivers' tables.
  bool own_load_path = t.contains("stage");
  for (const DriverKeys& d : drivers) own_load_path |= t.contains(d.table);
  if (own_load_path) {
    for (const DriverKeys& d : drivers)
      if (!t.contains(d.table)) merged.erase(d.table);
    if (!t.contains("stage")) merged.erase("stage");
  }
  merge_into(merged, std::move(t));
  return merged;
}

// The tables in the order their keys are checked (sections.hpp says where each is read).
void read_root(const toml::table& root, ModelConfig& cfg, const ModelFileKeys& keys) {
  TomlSection top(root, "", cfg.file.string());
  const std::string empty;
  cfg.title = top.string("title", &empty);
  cfg.seed = static_cast<std::uint64_t>(top.integer("seed", 1, 0));
  read_specimen_table(top, cfg);
  cfg.tessellation.seed = cfg.seed;
  read_blocks_table(top, cfg);
  read_joints_table(top, cfg);
  read_joint_set_tables(top, cfg);
  read_platens_table(top, cfg);
  read_contact_table(top, cfg);
  read_solver_table(top, cfg);
  read_loading_table(top, cfg);
  read_load_path(top, cfg, keys);
  read_quiet_boundary_table(top, cfg);
  read_in_situ_table(top, cfg);
  read_output_table(top, cfg);
  top.finish();
  check_lengths(root, cfg);
}

}  // namespace

ModelConfig read_model_file(const std::filesystem::path& file,
                            const std::vector<Override>& overrides, const ModelFileKeys& keys) {
  ModelConfig cfg;
  cfg.file = file;
  toml::table root = load(file, 0, cfg.sources, keys.drivers);
  for (const Override& o : overrides) apply_override(root, o, file.string());
  try {
    read_root(root, cfg, keys);
  } catch (const ModelFileError& e) {
    for (auto o = overrides.rbegin(); o != overrides.rend(); ++o) {  // the last one set the value
      if (!concerns(e.key(), o->key)) continue;
      fail_override(
          *o, file.string(),
          e.key() == o->key ? e.reason() : fmt::format("key '{}': {}", e.key(), e.reason()));
    }
    throw;
  }
  if (cfg.specimen_file) cfg.sources.push_back(*cfg.specimen_file);
  if (cfg.grains && cfg.grains->grain_file) cfg.sources.push_back(*cfg.grains->grain_file);
  return cfg;
}

}  // namespace vorodec::io
