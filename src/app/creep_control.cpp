#include "creep_control.hpp"

#include <algorithm>
#include <cmath>

namespace vorodec::app {

// A member added is either saved in CreepControl::serialize or comes from the model file (the
// stage); then update these sizes.
static_assert(sizeof(CreepControl) == 160, "CreepControl changed: see its serialize()");
static_assert(sizeof(CreepStageReport) == 48, "CreepStageReport changed: it is saved as bytes");

namespace {
// A window whose strain rate is this many times the stage's slowest is a collapse: secondary creep
// does not speed up a hundredfold, failure does.
constexpr double collapse_rate_factor = 100.0;
// Checks in a row with the stress below 90 % of its target: the servo cannot hold it.
constexpr long collapse_checks = 10;
// The step never falls below this fraction of its largest value.
constexpr double min_step_fraction = 1e-4;
}  // namespace

CreepControl::CreepControl(const loading::Stage& stage, solver::Solver& solver)
    : stage_(stage),
      max_dt_(stage.creep.time_step > 0 ? stage.creep.time_step
                                        : stage.creep.step_factor * solver.relaxation_time()),
      window_(stage.end.duration / 200.0) {
  solver.rescale_time_step(max_dt_);
  report_.max_time_step = report_.min_time_step = solver.dt();
}

bool CreepControl::after_step(solver::Solver& solver, const measure::SpecimenState& s, double ts) {
  ++report_.steps;
  if (!started_) {
    started_ = true;
    window_t0_ = ts;
    window_e0_ = s.axial_strain;
  }
  bool collapsed = false;
  if (ts >= window_t0_ + window_) {
    const double rate = (s.axial_strain - window_e0_) / (ts - window_t0_);
    // The first window holds the jolt of the stage's start and the fastest primary creep.
    if (!rates_.empty()) min_rate_ = std::min(min_rate_, std::max(rate, 0.0));
    rates_.push_back(rate);
    rate_ends_.push_back(ts);
    window_t0_ = ts;
    window_e0_ = s.axial_strain;
    collapsed =
        min_rate_ > 0 && std::isfinite(min_rate_) && rate > collapse_rate_factor * min_rate_;
  }
  const loading::CreepSettings& c = stage_.creep;
  if (solver.steps() % c.interval_steps == 0) {
    const double strain = solver.contact_strain_energy();
    if (strain > 0)
      report_.max_energy_ratio =
          std::max(report_.max_energy_ratio, solver.kinetic_energy() / strain);
    below_ = rates_.empty() || s.axial_stress >= 0.9 * stage_.target_stress ? 0 : below_ + 1;
    collapsed |= below_ >= collapse_checks;
    const double ratio = solver.unbalanced_force_ratio(), dt = solver.dt();
    double next = dt;
    if (!(ratio <= c.target_ratio))  // NaN shrinks too
      next = std::max(0.7 * dt, min_step_fraction * max_dt_);
    else if (ratio < c.target_ratio / 3)
      next = std::min(1.2 * dt, max_dt_);
    if (next != dt) {
      solver.rescale_time_step(next);
      report_.max_time_step = std::max(report_.max_time_step, solver.dt());
      report_.min_time_step = std::min(report_.min_time_step, solver.dt());
    }
  }
  if (collapsed) collapsed_at(ts);
  return collapsed;
}

// The start of the run of windows whose rate rose each time, up to the collapse.
double CreepControl::failure_onset() const {
  std::size_t i = rates_.size();
  while (i >= 2 && rates_[i - 1] > rates_[i - 2]) --i;
  return i >= 2 ? rate_ends_[i - 2] : 0.0;
}

}  // namespace vorodec::app
