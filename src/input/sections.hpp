#pragma once
// The model file's readers, one a table or two, private to src/input/. read_root (model_file.cpp)
// calls them in the order the keys are checked, which is the order their errors are reported in.
#include <toml++/toml.h>

#include <filesystem>
#include <limits>

#include "vorodec/input/model_file.hpp"
#include "vorodec/input/toml_section.hpp"

namespace vorodec::io {

// Limits that keep `vorodec check` and a run's set-up bounded (README.md, model file reference).
// The counts are estimated from the outline area before anything is tessellated.
constexpr double kMinLength = 1e-6;      // m, specimen dimensions and block, grain, sub-block sizes
constexpr double kMaxLength = 1e3;       // m
constexpr double kMaxBlocks = 1e6;       // blocks of a Voronoi specimen; grains; sub-blocks
constexpr double kMaxZones = 1e7;        // zones of deformable blocks, 2 x area / zone_size^2
constexpr double kMaxDamageCells = 1e6;  // area / damage_grid_cell^2
constexpr long kMaxLloydIterations = 100;
constexpr long kMaxCycles = 10'000;
constexpr long kMaxImplicitIncrements = 1'000;
constexpr long kMaxInt = std::numeric_limits<int>::max();  // keys kept in an int
// Mean Voronoi edge ~ 0.65 sqrt(area / blocks) (as src/geometry/voronoi_builder.cpp estimates).
constexpr double kPoissonEdgeFactor = 0.65;

// Without throwing: a path the system refuses (too long, no permission) counts as absent.
inline bool file_exists(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::exists(p, ec);
}

// The law a table chooses (`law`, default `default_law`) and that law's keys from the same table.
LawChoice read_law(TomlSection& sec, const std::string& default_law);

// The joints' law's nominal normal and shear springs (platen and quiet-boundary defaults).
laws::NominalStiffness nominal_stiffness(const LawChoice& c);

// A table's reader: the keys of one table of `top` (or of several) into `cfg`.
using TableReader = void(TomlSection& top, ModelConfig& cfg);

// specimen_keys.cpp: [specimen] with its [[mineral]] tables, then [blocks].
TableReader read_specimen_table, read_blocks_table;
// law_keys.cpp: [joints] (grain-based: by mineral and mineral pair), [platens], [contact].
TableReader read_joints_table, read_platens_table, read_contact_table;
// solver_output_keys.cpp: [solver], [loading], [output].
TableReader read_solver_table, read_loading_table, read_output_table;
// stage_keys.cpp: the load path. The stage modes' own top-level tables (such as [corrosion]), then
// a driver's table (such as [shpb]) or else the [[stage]] tables.
void read_load_path(TomlSection& top, ModelConfig& cfg, const ModelFileKeys& keys);
// joint_set_keys.cpp: the [[joint_set]] tables and the fracture files they name.
TableReader read_joint_set_tables;
// dynamics_keys.cpp: [quiet_boundary].
TableReader read_quiet_boundary_table;
// in_situ_keys.cpp: [in_situ].
TableReader read_in_situ_table;

// lengths.cpp: the specimen's lengths against one another, once every table is read.
void check_lengths(const toml::table& root, const ModelConfig& cfg);

}  // namespace vorodec::io
