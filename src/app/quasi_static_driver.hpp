#pragma once
// The quasi-static load path: the model file's stages in turn (platen velocity, stress servo,
// stress rate, creep, cyclic blocks), each until its end condition, with the confinement on the
// lateral boundary; an implicit elastic start where a stage asks for one.
#include <optional>

#include "corrosion_control.hpp"
#include "creep_control.hpp"
#include "driver.hpp"
#include "good_state.hpp"
#include "vorodec/io/model_file.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/loading/quiet_boundary.hpp"
#include "vorodec/loading/stage_control.hpp"

namespace vorodec::app {

class QuasiStaticDriver final : public Driver {
 public:
  // step_limit: steps after which the run stops; from_option: the limit is --max-steps (a short
  // run, exit 0), not the model file's solver.max_steps (exit 4).
  QuasiStaticDriver(const io::ModelConfig& cfg, model::Model& model, solver::Solver& solver,
                    const loading::SpecimenBoundary& boundary,
                    const geometry::Tessellation& specimen, long step_limit, bool from_option);

  void advance(Observers& observers) override;
  bool finished() const override { return phase_ == Phase::done; }
  bool resumable() const override { return phase_ == Phase::stepping; }
  RunView view() const override;
  ProgressReport progress() const override;
  const DriverOutcome& outcome() const override { return outcome_; }
  void save(checkpoint::OutArchive& ar) const override;
  void load(checkpoint::InArchive& ar) override;

 private:
  enum class Phase : int { stage_start, stepping, stage_end, done };
  template <class Archive>
  void state(Archive& ar);
  void start_stage(Observers& observers);
  void step(Observers& observers);
  void end_stage(Observers& observers);
  bool corrosion_step(Observers& observers);  // after a step of a corrosion stage: it ended
  const loading::Stage& stage() const { return cfg_.load_path.stages[si_]; }

  const io::ModelConfig& cfg_;
  model::Model& model_;
  solver::Solver& solver_;
  const loading::SpecimenBoundary& boundary_;
  const geometry::Tessellation& specimen_;
  long step_limit_;
  bool limit_from_option_;

  Phase phase_ = Phase::stage_start;
  std::size_t si_ = 0;  // current stage
  double t0_ = 0;       // s, its start time
  std::optional<loading::StageControl> control_;
  std::optional<CreepControl> creep_;            // creep stages
  std::optional<CorrosionControl> corrosion_;    // corrosion stages
  std::optional<loading::QuietBoundary> quiet_;  // from the model file (no state of its own)
  measure::SpecimenState state_;
  double v_ = 0;               // m/s, top platen
  double stage_fraction_ = 0;  // largest progress fraction of the stage so far
  GoodState good_;
  int resume_at_ = -1;  // a stalled cyclic block resumes here after its unloading
  bool stop_ = false;   // the step limit was reached
  DriverOutcome outcome_;
};

}  // namespace vorodec::app
