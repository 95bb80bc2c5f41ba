#pragma once
// The model file (TOML): every key documented in README.md, validated with file, key and line.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "vorodec/geometry/grains.hpp"
#include "vorodec/geometry/joints.hpp"
#include "vorodec/geometry/tessellation.hpp"
#include "vorodec/io/input_error.hpp"
#include "vorodec/laws/contact_law.hpp"
#include "vorodec/loading/in_situ.hpp"
#include "vorodec/loading/load_path.hpp"
#include "vorodec/loading/pressure_bar.hpp"
#include "vorodec/loading/quiet_boundary.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::io {

// One value replaced in a model file before it is read (`vorodec run --set`, batch files).
struct Override {
  std::string key;     // dotted path: "loading.confining_stress", "seed", "stage[0].end_time"
  std::string value;   // a TOML value: 5e6, 42, "linear_elastic", { weibull_shape = 4, mean = 1e7 }
  std::string origin;  // where it was given, for messages: "batch.toml:12", "--set"
};

struct LawChoice {
  std::string name;
  laws::LawParams params;
};

struct Mineral {
  std::string name;
  double fraction = 0;  // requested area fraction (0..1); unused with a grain file
  double density = 0;   // kg/m^3
  // Pa and plane-strain ratio of the mineral's zones when blocks are deformable (0: not given).
  double youngs_modulus = 0, poisson_ratio = 0;
};

// A grain-based specimen ([specimen] kind = "grains"): minerals and the contact laws inside grains
// (transgranular) and between grains (intergranular), by mineral and mineral pair.
struct GrainConfig {
  geometry::GrainSettings settings;
  std::optional<std::filesystem::path> grain_file;
  std::vector<Mineral> minerals;
  LawChoice intergranular, transgranular;        // defaults
  std::vector<std::optional<LawChoice>> inside;  // per mineral: its own transgranular law
  struct Pair {
    std::size_t a, b;  // minerals
    LawChoice law;     // intergranular law between grains of these minerals
  };
  std::vector<Pair> pairs;
};

// [quiet_boundary]: viscous boundaries on sides of the specimen's outline, and a half-sine
// particle-velocity pulse entering through one side (loading/quiet_boundary.hpp,
// docs/theory.md §15.2).
struct QuietBoundaryConfig {
  std::vector<loading::Side> sides;  // absorbing
  // m/s; 0: a row of rigid blocks' sqrt(jkn d / density) and sqrt(jks d / density), d the mean
  // block size (verification case A9)
  double p_wave_speed = 0, s_wave_speed = 0;
  std::optional<loading::Side> input_side;  // drives and absorbs
  double input_velocity = 0;                // m/s, peak of the half-sine
  double input_duration = 0;                // s
  bool input_shear = false;                 // along the side, not into it
};

struct OutputSettings {
  long history_steps = 200;       // steps between history rows
  long vtk_steps = 20000;         // steps between VTK frames (also at stage ends)
  double damage_grid_cell = 0.0;  // m, cell side of the damage grid; 0: about 5 mean block sizes
  long checkpoint_steps = 0;      // steps between checkpoints; 0: none by step count
  double checkpoint_wall_time = 600.0;  // s of wall time between checkpoints; 0: none by time
  // Acoustic-emission events (ae_events.csv): cracks within ae_radius m of each other, each
  // within ae_radius / ae_shear_wave_speed s of the last, are one event. 0: two mean block
  // sizes, and the shear-wave speed of a row of blocks sqrt(jks d / density)
  // (docs/theory.md §15.4).
  double ae_radius = 0.0;
  double ae_shear_wave_speed = 0.0;
};

// [blocks] deformable = true: specimen blocks zoned into constant-strain triangles (platens stay
// rigid).
struct DeformableSettings {
  bool enabled = false;
  double zone_size = 0;       // m, longest zone edge
  double youngs_modulus = 0;  // Pa
  double poisson_ratio = 0;   // plane strain
};

struct ModelConfig {
  std::filesystem::path file;
  // Every file the model was read from (the model file, its base files, a specimen or grain
  // file): a checkpoint's model hash covers them.
  std::vector<std::filesystem::path> sources;
  std::string title;
  std::uint64_t seed = 1;
  geometry::TessellationSettings tessellation;
  std::optional<std::filesystem::path> specimen_file;  // prepared specimen (vorodec build)
  int specimen_line = 0;                               // line of [specimen], for geometry errors
  std::string implicit_start_where;  // "file:line: key 'stage[0].implicit_start'", for run errors
  double density = 0;                // kg/m^3
  DeformableSettings deformable;     // [blocks] deformable, zone_size, E, nu
  double rounding_length = 0;        // m
  LawChoice joints;  // specimen block to block (grain-based: the default intergranular law)
  // [joints.mix]: this fraction of the specimen's joints (block pairs, drawn at random from the
  // seed) take a second law ([Guo2020]'s reading (b): Burger's and bonded contacts side by side).
  struct JointMix {
    double fraction = 0;  // -, in (0, 1)
    LawChoice law;
  };
  std::optional<JointMix> joint_mix;
  std::optional<GrainConfig> grains;  // grain-based specimen
  // [[joint_set]]: joint sets and fractures cutting a Voronoi specimen, each with its own law.
  struct JointSet {
    std::string name;
    std::optional<geometry::JointSetGeometry> statistics;  // dip, spacing, trace, gap, ...
    std::vector<geometry::JointTrace> fractures;           // from the set's or another set's file
    LawChoice law;
  };
  std::vector<JointSet> joint_sets;
  // The top-level tables the stage modes and drivers read themselves ([corrosion], [shpb]), by
  // name: what each one's reader made of it (StageModeKeys, DriverKeys).
  std::map<std::string, std::shared_ptr<const loading::ExtensionSettings>, std::less<>> tables;
  std::optional<QuietBoundaryConfig> quiet_boundary;
  std::optional<loading::InSituStress> in_situ;  // [in_situ]: the initial stress field
  LawChoice platens;                             // platen to specimen
  bool platens_bonded = false;                   // glued to the specimen (direct tension)
  solver::SolverSettings solver;
  long max_steps = 0;
  loading::LoadPath load_path;
  OutputSettings output;
};

class TomlSection;

// Reads a top-level table a stage mode or driver owns (called when the table is present, after
// [loading]; `top` is the root). Returns what the mode or driver keeps of it in
// ModelConfig::tables.
using OwnTableReader = std::shared_ptr<const loading::ExtensionSettings> (*)(
    TomlSection& table, TomlSection& top, const ModelConfig& cfg);

// A stage mode's model-file keys, read by the mode's own code (src/drivers/<mode>_mode.cpp): the
// [[stage]] tables with control = `control`, and the mode's top-level table if it has one.
struct StageModeKeys {
  const char* control;
  const char* table;  // nullptr: none
  OwnTableReader read_table;
  // A stage's keys but name, control, ramp_time, the end_* keys and the implicit start: the mode
  // sets the stage's control, target and own end conditions, and returns its settings.
  std::shared_ptr<const loading::ExtensionSettings> (*read_stage)(TomlSection& stage,
                                                                  loading::Stage& st,
                                                                  const ModelConfig& cfg);
};

// A driver's model-file keys: its top-level table, a load path of its own instead of [[stage]]s.
struct DriverKeys {
  const char* table;
  OwnTableReader read_table;
};

// The keys the stage modes and drivers read themselves (run::model_file_keys gives the registered
// ones).
struct ModelFileKeys {
  std::span<const StageModeKeys> modes;
  std::span<const DriverKeys> drivers;
};

// The settings a mode or driver read from its table `name`, nullptr if the file has none.
template <class Settings>
const Settings* table_settings(const ModelConfig& cfg, std::string_view name) {
  const auto at = cfg.tables.find(name);
  return at == cfg.tables.end() ? nullptr : static_cast<const Settings*>(at->second.get());
}

// Overrides are applied to the parsed file, so they are validated like the file's own keys; an
// error about an override names its origin instead of the model file's line.
ModelConfig read_model_file(const std::filesystem::path& file,
                            const std::vector<Override>& overrides, const ModelFileKeys& keys);

}  // namespace vorodec::io
