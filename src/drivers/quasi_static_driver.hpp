#pragma once
// The quasi-static load path: the model file's stages in turn (platen velocity, stress servo,
// stress rate, cyclic blocks), each until its end condition, with the confinement on the lateral
// boundary; an implicit elastic start where a stage asks for one; a stage mode (creep, corrosion:
// stage_modes.cpp) for the stages that have one.
#include <memory>
#include <optional>
#include <vector>

#include "driver_steps.hpp"
#include "implicit_start.hpp"
#include "stage_mode.hpp"
#include "vorodec/engine/driver.hpp"
#include "vorodec/engine/good_state.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/loading/quiet_boundary.hpp"
#include "vorodec/loading/stage_control.hpp"

namespace vorodec::run {

class QuasiStaticDriver final : public Driver, private ExtraColumns {
 public:
  explicit QuasiStaticDriver(const DriverContext& c);

  void advance(Observers& observers) override;
  bool finished() const override { return phase_ == Phase::done; }
  bool resumable() const override { return phase_ == Phase::stepping; }
  RunView view() const override;
  ProgressReport progress() const override;
  const DriverOutcome& outcome() const override { return outcome_; }
  void summarise(io::Json& summary) const override;
  void save(checkpoint::OutArchive& ar) const override;
  void load(checkpoint::InArchive& ar) override;

 private:
  enum class Phase : int { stage_start, stepping, stage_end, done };
  template <class Archive>
  void state(Archive& ar);
  void start_stage(Observers& observers);
  void step(Observers& observers);
  void end_stage(Observers& observers);
  const loading::Stage& stage() const { return cfg_.load_path.stages[si_]; }
  StageContext context() const { return {stage(), si_, t0_}; }
  StageMode* mode_of(const loading::Stage& stage) const;
  std::vector<std::string> column_names() const override;
  void column_values(std::vector<double>& row) const override;

  const io::ModelConfig& cfg_;
  model::Model& model_;
  solver::Solver& solver_;
  const loading::SpecimenBoundary& boundary_;
  const geometry::Tessellation& specimen_;
  StepLimit limit_;

  Phase phase_ = Phase::stage_start;
  std::size_t si_ = 0;  // current stage
  double t0_ = 0;       // s, its start time
  std::optional<loading::StageControl> control_;
  std::vector<std::unique_ptr<StageMode>> modes_;  // those the stages use
  StageMode* mode_ = nullptr;                      // the current stage's, if any
  std::optional<loading::QuietBoundary> quiet_;    // from the model file (no state of its own)
  std::optional<loading::InSituStress> in_situ_;   // from the model file, its datum resolved
  double in_situ_mid_xx_ = 0;  // Pa, its horizontal stress at mid-height (from the model file)
  measure::SpecimenState state_;
  double v_ = 0;               // m/s, top platen
  double stage_fraction_ = 0;  // largest progress fraction of the stage so far
  GoodState good_;
  int resume_at_ = -1;  // a stalled cyclic block resumes here after its unloading
  bool stop_ = false;   // the step limit was reached
  DriverOutcome outcome_;
  std::optional<ImplicitStart> implicit_start_;
};

}  // namespace vorodec::run
