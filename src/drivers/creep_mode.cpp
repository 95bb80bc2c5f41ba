#include "creep_mode.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "vorodec/io/json.hpp"
#include "vorodec/laws/contact_law.hpp"

namespace vorodec::run {

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
      max_dt_(creep_settings(stage).time_step > 0
                  ? creep_settings(stage).time_step
                  : creep_settings(stage).step_factor * solver.relaxation_time()),
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
  const CreepSettings& c = creep_settings(stage_);
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

namespace {

bool viscous_law(const io::LawChoice& c) {
  return laws::find_law(c.name)->make(c.params, 0)->viscous();
}

bool viscous_joints(const io::ModelConfig& cfg) {
  if (viscous_law(cfg.joints) || (cfg.joint_mix && viscous_law(cfg.joint_mix->law))) return true;
  if (!cfg.grains) return false;
  const io::GrainConfig& g = *cfg.grains;
  if (viscous_law(g.transgranular)) return true;
  for (const auto& in : g.inside)
    if (in && viscous_law(*in)) return true;
  for (const auto& p : g.pairs)
    if (viscous_law(p.law)) return true;
  return false;
}

}  // namespace

// control = "creep": the servo holds sigma1 = confining_stress + deviatoric_stress for a duration
// (s) or duration_days, at the creep step; the stage ends when its duration is up.
std::shared_ptr<const loading::ExtensionSettings> CreepMode::read_stage(
    io::TomlSection& sec, loading::Stage& st, const io::ModelConfig& cfg) {
  auto c = std::make_shared<CreepSettings>();
  st.control = loading::Control::axial_stress;
  st.target_stress =
      cfg.load_path.confining_stress + sec.positive("deviatoric_stress", laws::required);
  st.end.stress = st.target_stress;
  // The servo closes 80 % of the force error per step; a creep step is seconds long, so its speed
  // cap (m/s) is off unless given.
  st.platen_velocity = sec.positive("platen_velocity", 1e300);
  const bool seconds = sec.has("duration"), days = sec.has("duration_days");
  if (seconds == days)
    sec.fail(seconds ? "duration_days" : "duration",
             "a creep stage needs exactly one of duration (s) and duration_days (d)");
  st.end.duration = seconds ? sec.positive("duration", laws::required)
                            : 86400.0 * sec.positive("duration_days", laws::required);
  if (sec.has("end_time")) sec.fail("end_time", "a creep stage ends by duration or duration_days");
  c->step_factor = sec.positive("creep_step_factor", c->step_factor);
  if (sec.has("creep_time_step")) c->time_step = sec.positive("creep_time_step", 0);
  c->target_ratio = sec.positive("creep_target_ratio", c->target_ratio);
  c->interval_steps = sec.integer("creep_interval_steps", c->interval_steps, 1);
  if (cfg.deformable.enabled)
    sec.fail("control", "creep stages need rigid blocks ([blocks] deformable = false)");
  if (cfg.solver.fixed_time_step > 0)
    sec.fail("control", "creep stages set the step themselves: remove [solver] fixed_time_step");
  if (c->time_step == 0 && !viscous_joints(cfg))
    sec.fail("control",
             fmt::format("a creep stage sizes its step from the contacts' dashpots, and law '{}' "
                         "has none: use law = \"burgers\" or give creep_time_step (s)",
                         cfg.joints.name));
  return c;
}

// The start of the run of windows whose rate rose each time, up to the collapse.
double CreepControl::failure_onset() const {
  std::size_t i = rates_.size();
  while (i >= 2 && rates_[i - 1] > rates_[i - 2]) --i;
  return i >= 2 ? rate_ends_[i - 2] : 0.0;
}

ModeVerdict CreepMode::after_step(const StageContext& c, const measure::SpecimenState& s) {
  const double ts = solver_.time() - c.t0;
  if (!control_->after_step(solver_, s, ts)) return {};
  return {"",
          fmt::format("creep failure in stage '{}' after {:.4g} days", c.stage.name, ts / 86400.0),
          true, true};
}

std::string CreepMode::unstable(const StageContext& c, const std::string& what) {
  // A specimen that gives way under creep load.
  const double ts = solver_.time() - c.t0;
  control_->collapsed_at(ts);
  reports_.emplace_back(c.index, control_->report());
  control_.reset();
  return fmt::format("creep failure in stage '{}' after {:.4g} days, unstable: {}", c.stage.name,
                     ts / 86400.0, what);
}

void CreepMode::end_stage(const StageContext& c) {
  reports_.emplace_back(c.index, control_->report());
  control_.reset();
}

bool CreepMode::progress(const StageContext& c, ProgressReport& r) const {
  r.clock = fmt::format("day {:.3f} of {:.3f}", (solver_.time() - c.t0) / 86400.0,
                        c.stage.end.duration / 86400.0);
  return false;
}

// The creep step's range, how quasi-static each stage stayed, and any creep failure.
void CreepMode::summarise(io::Json& summary) const {
  if (reports_.empty()) return;
  const auto days = [](double t) { return io::rounded(t / 86400.0, 6); };
  io::Json rows = io::Json::array();
  for (const auto& [i, r] : reports_) {
    const loading::Stage& st = cfg_.load_path.stages[i];
    const double span = std::isnan(r.collapse) ? st.end.duration : r.collapse;
    rows.push_back(
        {{"stage", st.name},
         {"steps", r.steps},
         {"time_step_s", {io::rounded(r.min_time_step, 6), io::rounded(r.max_time_step, 6)}},
         {"steps_per_day", io::rounded(double(r.steps) / (span / 86400.0), 6)},
         {"max_kinetic_over_strain_energy", io::rounded(r.max_energy_ratio, 4)},
         {"failure_onset_days", days(r.failure_onset)},
         {"collapse_days", days(r.collapse)}});
  }
  summary["creep_stages"] = std::move(rows);
}

void CreepMode::save(checkpoint::OutArchive& ar) const {
  save_mode_state(ar, control_, reports_);
}

void CreepMode::load(checkpoint::InArchive& ar, const loading::Stage& current) {
  load_mode_state(ar, control_, reports_, current);
}

}  // namespace vorodec::run
