#pragma once
// The excavation mode (stages with control = "excavation", docs/loading.md#excavation): at the
// stage's start the blocks whose centroids lie inside a circle or polygon are removed
// (Solver::remove_blocks); the servo then holds the vertical stress and the confinement the
// horizontal one while the rock around the opening relaxes, slides on its joints, or falls in.
// With a relaxation time the removed blocks' last forces on the lining stay on as loads that fall
// linearly to zero over that time (a gradual release instead of a sudden one).
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stage_mode.hpp"
#include "vorodec/geometry/point.hpp"
#include "vorodec/input/toml_section.hpp"
#include "vorodec/loading/load_path.hpp"
#include "vorodec/measure/joint_displacement.hpp"

namespace vorodec::run {

struct ExcavationSettings final : loading::ExtensionSettings {
  // The opening: a circle (radius > 0) or else a counter-clockwise polygon.
  geometry::Point centre;  // m
  double radius = 0;       // m
  std::vector<geometry::Point> polygon;
  double fall_distance = 0;    // m, a block displaced this far since the excavation has fallen
  double relaxation_time = 0;  // s, over which the removed blocks' forces fall to zero
  bool inside(geometry::Point p) const;
  // The circle as a 64-gon, or the polygon (overlap checks).
  std::vector<geometry::Point> outline() const;
};

inline const ExcavationSettings& excavation_settings(const loading::Stage& stage) {
  return static_cast<const ExcavationSettings&>(*stage.mode_settings);
}

// What an excavation stage did (summary.json), and its history columns now.
struct ExcavationReport {
  double removed = 0;          // blocks
  double lining = 0;           // blocks that touched a removed one
  double convergence = 0;      // m, mean displacement of the lining towards the opening's centre
  double max_convergence = 0;  // m, the largest
  double fallen = 0;           // blocks displaced more than fall_distance
};

class ExcavationMode final : public StageMode {
 public:
  static std::shared_ptr<const loading::ExtensionSettings> read_stage(io::TomlSection& sec,
                                                                      loading::Stage& st,
                                                                      const io::ModelConfig& cfg);
  static constexpr io::StageModeKeys keys{"excavation", nullptr, nullptr, read_stage};

  explicit ExcavationMode(const DriverContext& c)
      : cfg_(c.cfg), model_(c.model), solver_(c.solver), joints_now_(2 * c.cfg.joint_sets.size()) {}
  void begin_stage(const StageContext& c) override;
  ModeVerdict after_step(const StageContext& c, const measure::SpecimenState& s) override;
  std::string unstable(const StageContext& c, const std::string& what) override;
  void end_stage(const StageContext& c) override;
  bool progress(const StageContext& c, ProgressReport& r) const override;
  std::vector<std::string> column_names() const override;
  void column_values(std::vector<double>& row) const override;
  void summarise(io::Json& summary) const override;
  void save(checkpoint::OutArchive& ar) const override;
  void load(checkpoint::InArchive& ar, const loading::Stage& current) override;

 private:
  void measure();
  void apply_relaxation();

  const io::ModelConfig& cfg_;
  model::Model& model_;
  solver::Solver& solver_;
  // The current (or last) excavation: its centre, its lining blocks and where every specimen
  // block stood when it was made.
  geometry::Point centre_;
  double fall_distance_ = 0;
  std::vector<std::uint32_t> lining_;
  measure::BlockPlacement at_;
  double removed_total_ = 0;
  ExcavationReport now_;
  std::vector<std::pair<std::size_t, ExcavationReport>> reports_;
  // The removed blocks' forces on each lining block (N per m, N m per m), and the release.
  std::vector<std::array<double, 3>> relaxation_load_;
  double start_time_ = 0, relaxation_time_ = 0;
  // Per [[joint_set]]: the largest slip and opening (m) of its contacts since the excavation;
  // and the same at the end of each reported stage (two per set, in reports_' order).
  std::vector<double> joints_now_, joint_reports_;
};

}  // namespace vorodec::run
