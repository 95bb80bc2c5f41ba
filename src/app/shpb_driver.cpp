#include "shpb_driver.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "observers.hpp"
#include "vorodec/checkpoint/archive_io.hpp"

namespace vorodec::app {

// A member added to the driver is either state a checkpoint carries (save and load it in
// ShpbDriver::state) or comes again from the model file (say so there); then update the size.
static_assert(sizeof(ShpbDriver) == 832, "ShpbDriver changed: see state()");

ShpbDriver::ShpbDriver(const io::ModelConfig& cfg, model::Model& model, solver::Solver& solver,
                       const loading::SpecimenBoundary& boundary,
                       const geometry::Tessellation& specimen, long step_limit, bool from_option)
    : cfg_(*cfg.shpb),
      model_(model),
      solver_(solver),
      boundary_(boundary),
      specimen_(specimen),
      step_limit_(step_limit),
      limit_from_option_(from_option),
      history_steps_(cfg.output.history_steps),
      vtk_steps_(cfg.output.vtk_steps),
      // The striker hits the bar's far end so that the pulse's front reaches the face at 0.
      incident_(cfg_.incident,
                loading::striker_pulse(cfg_.incident, cfg_.striker_length, cfg_.striker_velocity,
                                       -cfg_.incident.length / cfg_.incident.wave_speed(),
                                       cfg_.rise_time)),
      transmitted_(cfg_.transmitted, nullptr),
      bars_{cfg_, incident_, transmitted_, boundary.width(), boundary.height()},
      state_(measure::measure_specimen(model, boundary, solver)) {
  if (boundary.top_platen() < 0 || boundary.bottom_platen() < 0)
    throw std::runtime_error("a pressure-bar test needs both platens");
  solver_.set_face_control([this] { couple(); });
}

void ShpbDriver::couple() {
  auto& bl = model_.blocks;
  const auto top = static_cast<std::size_t>(boundary_.top_platen());
  const auto bottom = static_cast<std::size_t>(boundary_.bottom_platen());
  const double t = solver_.time(), mid = t + 0.5 * solver_.dt();
  // The specimen pushes the top platen up and the bottom one down (N per m): compression +.
  const double s_in = solver_.contact_force(top).y / cfg_.incident.width;
  const double s_tr = -solver_.contact_force(bottom).y / cfg_.transmitted.width;
  incident_.record_face(t, s_in);
  transmitted_.record_face(t, s_tr);
  // The step's velocity is the half step's: the face stress extrapolated there.
  const double h_in = coupled_ ? 1.5 * s_in - 0.5 * last_incident_ : s_in;
  const double h_tr = coupled_ ? 1.5 * s_tr - 0.5 * last_transmitted_ : s_tr;
  bl.vx[top] = bl.vx[bottom] = bl.omega[top] = bl.omega[bottom] = 0.0;
  bl.vy[top] = -incident_.face_velocity(mid, h_in);
  bl.vy[bottom] = transmitted_.face_velocity(mid, h_tr);
  last_incident_ = s_in;
  last_transmitted_ = s_tr;
  coupled_ = true;
}

RunView ShpbDriver::view() const {
  const double v = -model_.blocks.vy[static_cast<std::size_t>(boundary_.top_platen())];
  return {model_, solver_, specimen_, state_, v, 0, false, false, 0.0, &bars_};
}

void ShpbDriver::advance(Observers& observers) {
  try {
    if (phase_ == Phase::start) {
      observers.sample(view(), {"impact:start", true, false});
      phase_ = Phase::stepping;
    } else if (phase_ == Phase::stepping) {
      step(observers);
    }
  } catch (const solver::InstabilityError& e) {
    outcome_.exit_code = 3;
    outcome_.status = fmt::format("unstable: {}", e.what());
    good_.restore(model_);
    observers.sample(view(), {"unstable", false, true});
    phase_ = Phase::done;
  }
}

void ShpbDriver::step(Observers& observers) {
  if (solver_.time() >= cfg_.duration) return finish(observers, "impact:end");
  if (solver_.steps() >= step_limit_) {
    outcome_.status = limit_from_option_ ? "stopped at --max-steps" : "step limit";
    outcome_.exit_code = limit_from_option_ ? 0 : 4;
    return finish(observers, "impact:stopped");
  }
  solver_.step();
  state_ = measure::measure_specimen(model_, boundary_, solver_);
  if (solver_.steps() % 100 == 0) {
    solver_.check_stability();
    good_.keep(model_);
  }
  outcome_.peak = std::max(outcome_.peak, state_.axial_stress);
  outcome_.trough = std::min(outcome_.trough, state_.axial_stress);
  const bool row = solver_.steps() % history_steps_ == 0;
  const bool frame = solver_.steps() % vtk_steps_ == 0;
  if (row || frame) observers.sample(view(), {"impact", row, frame});
}

void ShpbDriver::finish(Observers& observers, const std::string& label) {
  observers.sample(view(), {label, true, true});
  phase_ = Phase::done;
}

ProgressReport ShpbDriver::progress() const {
  ProgressReport r;
  r.stage_name = "impact";
  r.steps = solver_.steps();
  r.stress = state_.axial_stress;
  r.fraction = std::clamp(solver_.time() / cfg_.duration, 0.0, 1.0);
  return r;
}

template <class Archive>
void ShpbDriver::state(Archive& ar) {
  using checkpoint::pod;
  int phase = static_cast<int>(phase_);
  ar(phase, last_incident_, last_transmitted_, coupled_, checkpoint::bytes(state_), good_);
  for (loading::ElasticBar* b : {&incident_, &transmitted_})
    ar(pod(b->face_history().times()), pod(b->face_history().values()));
  ar(outcome_.exit_code, outcome_.status, outcome_.peak, outcome_.trough);
  phase_ = static_cast<Phase>(phase);
}

void ShpbDriver::save(checkpoint::OutArchive& ar) const {
  const_cast<ShpbDriver*>(this)->state(ar);  // saving only reads
}

void ShpbDriver::load(checkpoint::InArchive& ar) {
  state(ar);
}

}  // namespace vorodec::app
