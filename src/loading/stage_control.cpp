#include "vorodec/loading/stage_control.hpp"

#include <algorithm>
#include <cmath>

namespace vorodec::loading {

StageControl::StageControl(const Stage& stage, double v_previous, double stress0, double strain0)
    : st_(stage),
      v0_(v_previous),
      v_(stage.platen_velocity),
      stress0_(stress0),
      strain0_(strain0),
      v_from_(stage.platen_velocity) {
  if (!std::isnan(st_.end.axial_stress)) rising_ = st_.end.axial_stress > stress0;
}

double StageControl::target(double ts) const {
  if (st_.control == Control::axial_stress) return st_.target_stress;
  double t = stress0_ + st_.stress_rate * ts;
  // The target stops at the stage's end stress so the servo does not overshoot it.
  if (!std::isnan(st_.end.axial_stress))
    t = rising_ ? std::min(t, st_.end.axial_stress) : std::max(t, st_.end.axial_stress);
  return t;
}

double StageControl::platen_velocity(double ts, double stress, double k, double dt,
                                     double width) const {
  if (st_.control == Control::platen_velocity) {
    // An adaptive change is spread over its interval: a jump would jolt the specimen, and the
    // controller would read its own jolt as unbalance.
    const double u = t_span_ > 0 ? std::clamp((ts - t_adapt_) / t_span_, 0.0, 1.0) : 1.0;
    const double v = v_from_ + (v_ - v_from_) * u;
    return ts < st_.ramp_time ? v0_ + (v - v0_) * ts / st_.ramp_time : v;
  }
  // Servo on the top platen (PFC wall servo): closes 80 % of the force error in one step.
  const double df = (target(ts) - stress) * width;
  const double v = k > 0 ? 0.8 * df / (k * dt) : st_.platen_velocity;
  const double cap = st_.platen_velocity;
  if (st_.control == Control::stress_rate) {
    // A ramp never drives the platen against its direction: an unloading specimen that loses
    // stress by itself (post-peak) is not pushed back up to the target, the platen waits.
    return st_.stress_rate < 0 ? std::clamp(v, -cap, 0.0) : std::clamp(v, 0.0, cap);
  }
  return std::clamp(v, -cap, cap);
}

void StageControl::adapt(double ratio, double ts, double dt) {
  const AdaptiveVelocity& a = st_.adaptive;
  v_from_ = platen_velocity(ts, 0, 0, dt, 0);
  t_adapt_ = ts;
  t_span_ = static_cast<double>(a.interval_steps) * dt;
  // The square root halves the log-distance to the target per update: the ratio grows roughly
  // in proportion to the speed, so a full step would overshoot on its noise. A NaN ratio slows.
  const double f = ratio > 0 ? std::sqrt(a.target_ratio / ratio) : ratio == 0 ? a.max_change : 0.0;
  v_ = std::clamp(v_ * std::clamp(f, 1.0 / a.max_change, a.max_change), a.min_velocity,
                  a.max_velocity);
}

StageOutcome StageControl::judge(const StageSample& s) {
  const StageEnd& end = st_.end;
  double fraction = 0.0;
  bool done = false;
  if (!std::isnan(end.axial_strain)) {
    const double span = end.axial_strain - strain0_;
    fraction = std::max(fraction, span != 0 ? (s.axial_strain - strain0_) / span : 1.0);
    done |= span >= 0 ? s.axial_strain >= end.axial_strain : s.axial_strain <= end.axial_strain;
  }
  bool past_peak = false;
  // Pulling platens (direct tension): peaks are judged on the tensile stress.
  const bool pulling = st_.control == Control::platen_velocity && st_.platen_velocity < 0;
  const double load = pulling ? -s.axial_stress : s.axial_stress;
  if (s.history_row) {
    // Judged on history rows: the peak must lie three rows back, so start-up noise is no peak.
    if (load > row_peak_) {
      row_peak_ = load;
      rows_since_peak_ = 0;
    } else {
      ++rows_since_peak_;
    }
    // A peak counts once the stress has risen 0.1 MPa above its start: a stage that begins at a
    // low stress while its velocity ramps up (after an unloading) is not past a peak. In
    // compression it must also exceed the confinement (see StageSample::confining_stress).
    const double floor = std::max(stress0_, pulling ? 0.0 : s.confining_stress);
    past_peak = row_peak_ > std::max(floor, 0.0) + 1e5 && rows_since_peak_ >= 3;
    past_peak_ = past_peak;
  }
  if (!std::isnan(end.post_peak_fraction) && past_peak) {
    const double drop = (1.0 - load / row_peak_) / (1.0 - end.post_peak_fraction);
    fraction = std::max(fraction, std::clamp(drop, 0.0, 1.0));
    done |= load < end.post_peak_fraction * row_peak_;
  }
  if (!std::isnan(end.stress)) {
    const bool near = std::abs(s.axial_stress - end.stress) <= 0.01 * std::max(end.stress, 1e5);
    held_ = near ? held_ + 1 : 0;
    if (std::isnan(end.duration)) done |= held_ >= 200;
  }
  if (!std::isnan(end.duration)) {
    fraction = std::max(fraction, s.time_in_stage / end.duration);
    done |= s.time_in_stage >= end.duration;
  }
  if (!std::isnan(end.axial_stress)) {
    const double span = end.axial_stress - stress0_;
    fraction = std::max(fraction, span != 0 ? (s.axial_stress - stress0_) / span : 1.0);
    // An unloading servo approaches its end stress asymptotically: 0.1 % of the span counts.
    const double slack = 1e-3 * std::abs(span);
    done |= rising_ ? s.axial_stress >= end.axial_stress - slack
                    : s.axial_stress <= end.axial_stress + slack;
  }
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  if (done) return StageOutcome::done;
  // Loading towards a stress it can no longer reach: the curve has peaked below it.
  if (rising_ && !std::isnan(end.axial_stress) && st_.control == Control::platen_velocity &&
      past_peak && row_peak_ >= stress0_ + 0.5 * (end.axial_stress - stress0_))
    return StageOutcome::stalled;
  return StageOutcome::running;
}

void append_cycles(const CyclicBlock& block, std::vector<Stage>& stages) {
  const int after = static_cast<int>(stages.size() + 2 * block.upper_stresses.size());
  for (std::size_t k = 0; k < block.upper_stresses.size(); ++k) {
    const int cycle = static_cast<int>(k + 1);
    Stage load;
    load.name = block.name + std::to_string(cycle) + "_load";
    load.control = Control::platen_velocity;
    load.platen_velocity = block.loading_velocity;
    load.ramp_time = block.ramp_time;
    load.end.axial_stress = block.upper_stresses[k];
    load.cycle = cycle;
    load.phase = CyclePhase::loading;
    Stage unload;
    unload.name = block.name + std::to_string(cycle) + "_unload";
    unload.control = Control::stress_rate;
    unload.stress_rate = -block.unloading_rate;
    unload.platen_velocity = block.servo_velocity_cap;
    unload.end.axial_stress = block.lower_stress;
    unload.cycle = cycle;
    unload.phase = CyclePhase::unloading;
    load.block_end = unload.block_end = after;
    stages.push_back(load);
    stages.push_back(unload);
  }
}

}  // namespace vorodec::loading
