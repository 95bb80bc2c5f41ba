#pragma once
// The creep mode (stages with control = "creep"). A creep stage's clock: the creep step (density
// scaling sized to the contacts' relaxation time, adapted by the unbalanced-force ratio), how
// quasi-static the stage stayed (its largest kinetic over strain energy), and creep failure: the
// collapse that ends the stage and the onset of the accelerating (tertiary) creep before it.
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stage_mode.hpp"
#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/input/toml_section.hpp"
#include "vorodec/loading/load_path.hpp"
#include "vorodec/measure/specimen.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::run {

// A creep stage (an axial-stress stage that holds sigma1 - sigma3): the mechanical step is the
// creep step, with density scaling sized to it (PFC's and UDEC's creep modes), and the run
// watches for creep failure.
struct CreepSettings final : loading::ExtensionSettings {
  // -, the largest creep step as a fraction of the contacts' shortest relaxation time (Ck/Kk or
  // Cm/Km); time_step > 0 (s) gives it directly instead.
  double step_factor = 1e-3;
  double time_step = 0.0;
  // The step shrinks (x 0.7) while the unbalanced-force ratio is above target_ratio, and grows
  // back (x 1.2, up to the largest) while it is below a third of it; checked every interval_steps.
  double target_ratio = 1e-3;
  long interval_steps = 100;
};

inline const CreepSettings& creep_settings(const loading::Stage& stage) {
  return static_cast<const CreepSettings&>(*stage.mode_settings);
}

// What a creep stage did (summary.json).
struct CreepStageReport {
  double max_time_step = 0, min_time_step = 0;  // s, the creep step's range in the stage
  double max_energy_ratio = 0;                  // -, largest kinetic / contact strain energy
  long steps = 0;
  double failure_onset = std::numeric_limits<double>::quiet_NaN();  // s in the stage
  double collapse = std::numeric_limits<double>::quiet_NaN();       // s in the stage
};

class CreepControl {
 public:
  // Starts the stage: sets the solver's step to the stage's creep step.
  CreepControl(const loading::Stage& stage, solver::Solver& solver);
  // A control whose state a checkpoint then loads (the solver's step is loaded with the solver).
  explicit CreepControl(const loading::Stage& stage) : stage_(stage), max_dt_(0), window_(0) {}
  // After each step of the stage (s: the specimen after it, ts: time in the stage); true once the
  // specimen has collapsed.
  bool after_step(solver::Solver& solver, const measure::SpecimenState& s, double ts);
  // The specimen collapsed at time ts in the stage some other way (the run's stability checks).
  void collapsed_at(double ts) {
    report_.collapse = ts;
    report_.failure_onset = failure_onset();
  }
  const CreepStageReport& report() const { return report_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(max_dt_, window_, window_t0_, window_e0_, min_rate_, below_, started_,
       checkpoint::bytes(report_), checkpoint::pod(rates_), checkpoint::pod(rate_ends_));
  }

 private:
  double failure_onset() const;

  const loading::Stage& stage_;
  double max_dt_;
  double window_;  // s, span of one strain-rate window: a 200th of the stage
  double window_t0_ = 0, window_e0_ = 0;
  double min_rate_ = std::numeric_limits<double>::infinity();  // 1/s, over windows after the first
  long below_ = 0;  // consecutive checks with the stress below 90 % of its target
  bool started_ = false;
  CreepStageReport report_;
  std::vector<double> rates_, rate_ends_;  // 1/s and s in the stage, per finished window
};

class CreepMode final : public StageMode {
 public:
  // The model-file keys of a creep stage (docs/model-file.md, "Creep stages").
  static std::shared_ptr<const loading::ExtensionSettings> read_stage(io::TomlSection& sec,
                                                                      loading::Stage& st,
                                                                      const io::ModelConfig& cfg);
  static constexpr io::StageModeKeys keys{"creep", nullptr, nullptr, read_stage};

  explicit CreepMode(const DriverContext& c) : cfg_(c.cfg), solver_(c.solver) {}
  void begin_stage(const StageContext& c) override { control_.emplace(c.stage, solver_); }
  bool sets_time_step() const override { return true; }
  ModeVerdict after_step(const StageContext& c, const measure::SpecimenState& s) override;
  std::string unstable(const StageContext& c, const std::string& what) override;
  void end_stage(const StageContext& c) override;
  bool progress(const StageContext& c, ProgressReport& r) const override;
  // Creep runs tell their time in days too.
  std::vector<std::string> column_names() const override { return {"time_days"}; }
  void column_values(std::vector<double>& row) const override {
    row.push_back(solver_.time() / 86400.0);
  }
  void summarise(io::Json& summary) const override;
  void save(checkpoint::OutArchive& ar) const override;
  void load(checkpoint::InArchive& ar, const loading::Stage& current) override;

 private:
  const io::ModelConfig& cfg_;
  solver::Solver& solver_;
  std::optional<CreepControl> control_;                            // in a creep stage
  std::vector<std::pair<std::size_t, CreepStageReport>> reports_;  // (stage index, report)
};

}  // namespace vorodec::run
