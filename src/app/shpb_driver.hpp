#pragma once
// The split Hopkinson pressure bar test (PHYSICS 15): exact 1D elastic bars (loading/
// pressure_bar.hpp) whose faces are the platens. In every step the solver's face control reads
// the specimen's force on each platen, records it as the bar face's stress, and gives the platen
// the face's velocity for the step. Time 0 is the incident pulse's arrival at the specimen; the
// test runs for [shpb] duration.
#include "driver.hpp"
#include "good_state.hpp"
#include "vorodec/io/model_file.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/loading/pressure_bar.hpp"

namespace vorodec::app {

class ShpbDriver final : public Driver {
 public:
  ShpbDriver(const io::ModelConfig& cfg, model::Model& model, solver::Solver& solver,
             const loading::SpecimenBoundary& boundary, const geometry::Tessellation& specimen,
             long step_limit, bool from_option);
  ~ShpbDriver() override { solver_.set_face_control({}); }
  ShpbDriver(const ShpbDriver&) = delete;
  ShpbDriver& operator=(const ShpbDriver&) = delete;

  void advance(Observers& observers) override;
  bool finished() const override { return phase_ == Phase::done; }
  bool resumable() const override { return phase_ == Phase::stepping; }
  RunView view() const override;
  ProgressReport progress() const override;
  const DriverOutcome& outcome() const override { return outcome_; }
  void save(checkpoint::OutArchive& ar) const override;
  void load(checkpoint::InArchive& ar) override;

 private:
  enum class Phase : int { start, stepping, done };
  template <class Archive>
  void state(Archive& ar);
  void step(Observers& observers);
  void finish(Observers& observers, const std::string& label);
  void couple();  // the solver's face control

  const io::ShpbConfig& cfg_;
  model::Model& model_;
  solver::Solver& solver_;
  const loading::SpecimenBoundary& boundary_;
  const geometry::Tessellation& specimen_;
  long step_limit_;
  bool limit_from_option_;
  long history_steps_, vtk_steps_;

  loading::ElasticBar incident_, transmitted_;
  BarsView bars_;
  // Pa, each face's stress in the last step (the half-step extrapolation's); NaN before.
  double last_incident_ = 0, last_transmitted_ = 0;
  bool coupled_ = false;  // a step has been coupled (the last stresses are set)
  Phase phase_ = Phase::start;
  measure::SpecimenState state_;
  GoodState good_;
  DriverOutcome outcome_;
};

}  // namespace vorodec::app
