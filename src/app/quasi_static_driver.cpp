#include "quasi_static_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "implicit_start.hpp"
#include "observers.hpp"
#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/solver/elastic_response.hpp"

namespace vorodec::app {

// A member added to the driver is either state a checkpoint carries (save and load it in
// QuasiStaticDriver::state) or comes again from the model file or the loaded state (say so there);
// then update these sizes.
static_assert(sizeof(QuasiStaticDriver) == 1152, "QuasiStaticDriver changed: see state()");
static_assert(sizeof(DriverOutcome) == 264, "DriverOutcome changed: see state()");
static_assert(sizeof(loading::StageControl) == 104, "StageControl changed: see its serialize()");

namespace {

// m, sqrt(specimen area / specimen blocks), the areas from the block polygons.
double mean_block_size(const model::Model& m) {
  const auto& bl = m.blocks;
  double area = 0;
  std::size_t n = 0;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    if (bl.group[b] != model::Group::specimen) continue;
    ++n;
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c)
      area += 0.5 * cross(bl.corner[c], bl.corner[bl.next_corner(b, c)]);
  }
  return n ? std::sqrt(area / static_cast<double>(n)) : 0.0;
}

loading::QuietBoundary make_quiet_boundary(const io::QuietBoundaryConfig& q,
                                           const io::ModelConfig& cfg, const model::Model& m) {
  const double d = mean_block_size(m);
  const auto speed = [&](double given, const char* key) {
    const auto k = cfg.joints.params.find(key);
    return given > 0 ? given : std::sqrt(k->second.mean() * d / cfg.density);
  };
  std::vector<loading::BoundaryEdge> edges;
  for (const loading::Side s : q.sides) {
    const auto e = loading::outline_edges(m, s);
    edges.insert(edges.end(), e.begin(), e.end());
  }
  loading::QuietBoundary quiet(
      edges, {cfg.density, speed(q.p_wave_speed, "jkn"), speed(q.s_wave_speed, "jks")});
  if (q.input_side) {
    const double v = q.input_velocity, duration = q.input_duration;
    const bool shear = q.input_shear;
    quiet.set_input(loading::outline_edges(m, *q.input_side), [=](double t) {
      const double u = t < duration ? v * std::sin(std::numbers::pi * t / duration) : 0.0;
      return shear ? loading::InputVelocity{0.0, u} : loading::InputVelocity{u, 0.0};
    });
  }
  return quiet;
}

}  // namespace

QuasiStaticDriver::QuasiStaticDriver(const io::ModelConfig& cfg, model::Model& model,
                                     solver::Solver& solver,
                                     const loading::SpecimenBoundary& boundary,
                                     const geometry::Tessellation& specimen, long step_limit,
                                     bool from_option)
    : cfg_(cfg),
      model_(model),
      solver_(solver),
      boundary_(boundary),
      specimen_(specimen),
      step_limit_(step_limit),
      limit_from_option_(from_option),
      state_(measure::measure_specimen(model, boundary, solver)) {
  outcome_.stalled.assign(cfg.load_path.stages.size(), false);
  if (cfg.load_path.stages.empty()) phase_ = Phase::done;
  if (cfg.quiet_boundary) quiet_.emplace(make_quiet_boundary(*cfg.quiet_boundary, cfg, model));
}

RunView QuasiStaticDriver::view() const {
  const auto& stages = cfg_.load_path.stages;
  const bool creep = std::any_of(stages.begin(), stages.end(),
                                 [](const loading::Stage& s) { return s.creep.enabled; });
  const bool corrosion = std::any_of(stages.begin(), stages.end(),
                                     [](const loading::Stage& s) { return s.corrosion.enabled; });
  const double clock = corrosion_                   ? corrosion_->time()
                       : outcome_.corrosion.empty() ? 0.0
                                                    : outcome_.corrosion.back().second.time;
  return {model_, solver_, specimen_, state_, v_, static_cast<int>(si_), creep, corrosion, clock};
}

void QuasiStaticDriver::advance(Observers& observers) {
  try {
    switch (phase_) {
      case Phase::stage_start:
        start_stage(observers);
        break;
      case Phase::stepping:
        step(observers);
        break;
      case Phase::stage_end:
        end_stage(observers);
        break;
      case Phase::done:
        break;
    }
  } catch (const solver::InstabilityError& e) {
    outcome_.exit_code = 3;
    outcome_.status = fmt::format("unstable: {}", e.what());
    if (creep_ && phase_ == Phase::stepping) {  // a specimen that gives way under creep load
      const double ts = solver_.time() - t0_;
      creep_->collapsed_at(ts);
      outcome_.creep.emplace_back(si_, creep_->report());
      outcome_.status = fmt::format("creep failure in stage '{}' after {:.4g} days, unstable: {}",
                                    stage().name, ts / 86400.0, e.what());
    }
    if (corrosion_ && phase_ == Phase::stepping) {  // static fatigue: the collapse went unstable
      CorrosionStageReport r = corrosion_->report();
      r.failure_time = r.time;
      outcome_.corrosion.emplace_back(si_, r);
      outcome_.status = fmt::format(
          "static-fatigue failure in stage '{}' after {:.4g} s of corrosion, "
          "unstable: {}",
          stage().name, r.time, e.what());
      solver_.set_crack_clock(std::numeric_limits<double>::quiet_NaN());
    }
    good_.restore(model_);
    observers.sample(view(), {"unstable", false, true});
    phase_ = Phase::done;
  }
}

void QuasiStaticDriver::start_stage(Observers& observers) {
  const loading::Stage& st = stage();
  t0_ = solver_.time();
  stage_fraction_ = 0;
  control_.emplace(st, v_, state_.axial_stress, state_.axial_strain);
  creep_.reset();
  corrosion_.reset();
  if (st.corrosion.enabled) {
    corrosion_.emplace(st, *cfg_.corrosion, model_, solver_, specimen_.block_grain);
    solver_.set_crack_clock(0.0);
  }
  if (st.creep.enabled)
    creep_.emplace(st, solver_);
  else if (solver_.scaling_time_step() != cfg_.solver.time_step)  // after a creep stage
    solver_.rescale_time_step(cfg_.solver.time_step);
  observers.sample(view(), {st.name + ":start", true, false});
  if (st.implicit_start) {
    try {
      outcome_.implicit_start =
          implicit_start(model_, solver_, boundary_, st, cfg_.load_path.confining_stress);
    } catch (const solver::ElasticResponseError& e) {
      throw io::ModelFileError(fmt::format("{}: {}", cfg_.implicit_start_where, e.what()),
                               fmt::format("stage[{}].implicit_start", si_), e.what());
    }
    state_ = measure::measure_specimen(model_, boundary_, solver_);
    outcome_.peak = std::max(outcome_.peak, state_.axial_stress);
    observers.sample(view(), {st.name + ":implicit", true, false});
  }
  phase_ = Phase::stepping;
}

void QuasiStaticDriver::step(Observers& observers) {
  if (solver_.steps() >= step_limit_) {
    outcome_.status = limit_from_option_ ? "stopped at --max-steps" : "step limit";
    outcome_.exit_code = limit_from_option_ ? 0 : 4;
    stop_ = true;
    phase_ = Phase::stage_end;
    return;
  }
  const loading::Stage& st = stage();
  loading::StageControl& control = *control_;
  const double ts = solver_.time() - t0_;
  // Adaptive speed: after the ramp, every interval_steps, from the last step's forces.
  if (st.adaptive.enabled && ts >= st.ramp_time &&
      solver_.steps() % st.adaptive.interval_steps == 0)
    control.adapt(solver_.unbalanced_force_ratio(), ts, solver_.dt());
  v_ = control.platen_velocity(
      ts, state_.axial_stress,
      solver_.contact_stiffness_on(static_cast<std::size_t>(boundary_.top_platen())), solver_.dt(),
      boundary_.width());
  boundary_.set_platen_velocity(model_, v_);
  if (quiet_) quiet_->clear_loads(model_);
  boundary_.apply_confinement(model_, cfg_.load_path.confining_stress);
  if (quiet_) quiet_->apply(model_, solver_.time());
  solver_.step();
  state_ = measure::measure_specimen(model_, boundary_, solver_);
  good_.check(solver_, model_);
  outcome_.peak = std::max(outcome_.peak, state_.axial_stress);
  outcome_.trough = std::min(outcome_.trough, state_.axial_stress);
  const bool row = solver_.steps() % cfg_.output.history_steps == 0;
  const bool frame = solver_.steps() % cfg_.output.vtk_steps == 0;
  if (row || frame) observers.sample(view(), {st.name, row, frame});
  const loading::StageOutcome outcome =
      control.judge({solver_.time() - t0_, state_.axial_stress, state_.axial_strain, row});
  stage_fraction_ = std::max(stage_fraction_, control.fraction());
  if (creep_ && creep_->after_step(solver_, state_, solver_.time() - t0_)) {
    outcome_.status = fmt::format("creep failure in stage '{}' after {:.4g} days", st.name,
                                  (solver_.time() - t0_) / 86400.0);
    stop_ = true;
    phase_ = Phase::stage_end;
    return;
  }
  if (corrosion_ && corrosion_step(observers)) {
    phase_ = Phase::stage_end;
    return;
  }
  if (outcome == loading::StageOutcome::stalled) {
    outcome_.stalled[si_] = true;
    resume_at_ = st.block_end;
  }
  if (outcome != loading::StageOutcome::running) phase_ = Phase::stage_end;
}

bool QuasiStaticDriver::corrosion_step(Observers& observers) {
  const loading::Stage& st = stage();
  switch (corrosion_->after_step(solver_, model_, state_)) {
    case CorrosionControl::Next::step:
      return false;
    case CorrosionControl::Next::corroded:
      observers.sample(view(), {st.name + ":equilibrium", true, false});
      return false;
    case CorrosionControl::Next::collapsed:
      outcome_.status = fmt::format(
          "static-fatigue failure in stage '{}' after {:.4g} s ({:.4g} days) of corrosion: no "
          "equilibrium within {} steps",
          st.name, corrosion_->report().failure_time, corrosion_->report().failure_time / 86400.0,
          st.corrosion.max_equilibrium_steps);
      stop_ = true;
      return true;
    case CorrosionControl::Next::no_corrosion:
      outcome_.status = fmt::format(
          "stage '{}': no bond corrodes at this stress (none above its activation): no "
          "static-fatigue failure",
          st.name);
      return true;
    case CorrosionControl::Next::time_up:
      return true;
  }
  return false;
}

void QuasiStaticDriver::end_stage(Observers& observers) {
  const loading::Stage& st = stage();
  const std::string label = st.name + (outcome_.stalled[si_] ? ":stalled" : ":end");
  if (creep_) outcome_.creep.emplace_back(si_, creep_->report());
  if (corrosion_) {
    outcome_.corrosion.emplace_back(si_, corrosion_->report());
    solver_.set_crack_clock(std::numeric_limits<double>::quiet_NaN());
  }
  observers.sample(view(), {label, true, true});
  std::size_t next = si_ + 1;
  if (resume_at_ >= 0 && st.phase == loading::CyclePhase::unloading) {
    next = static_cast<std::size_t>(resume_at_);
    resume_at_ = -1;
  }
  if (stop_ || next >= cfg_.load_path.stages.size()) {
    phase_ = Phase::done;
    return;
  }
  si_ = next;
  phase_ = Phase::stage_start;
}

ProgressReport QuasiStaticDriver::progress() const {
  ProgressReport r;
  r.stage = si_;
  r.stages = cfg_.load_path.stages.size();
  r.steps = solver_.steps();
  r.stress = state_.axial_stress;
  if (phase_ == Phase::done || si_ >= r.stages) return r;
  const loading::Stage& st = stage();
  r.stage_name = st.name;
  if (st.creep.enabled)
    r.clock = fmt::format("day {:.3f} of {:.3f}", (solver_.time() - t0_) / 86400.0,
                          st.end.duration / 86400.0);
  if (corrosion_) {
    const CorrosionStageReport& c = corrosion_->report();
    r.clock = fmt::format("corrosion {:.4g} s = {:.4g} days = {:.3g} years, step {}", c.time,
                          c.time / 86400.0, c.time / (365.25 * 86400.0), c.corrosion_steps);
    // When the specimen fails is what the stage finds out: no percentage.
    r.waiting = fmt::format("static fatigue: until collapse; {} tensile + shear cracks",
                            solver_.cracks().size());
    return r;
  }
  if (std::isnan(st.end.post_peak_fraction)) {
    r.fraction = stage_fraction_;
    return r;
  }
  // The end waits for the stress to fall after a peak no one can know ahead: no percentage.
  const double peak = control_ ? control_->peak() : 0.0;
  if (control_ && control_->past_peak())
    r.waiting = fmt::format("post-peak: stress {:.2f} of {:.2f} MPa target",
                            state_.axial_stress / 1e6, st.end.post_peak_fraction * peak / 1e6);
  else
    r.waiting = fmt::format("towards the peak: highest so far {:.2f} MPa",
                            std::max(peak, state_.axial_stress) / 1e6);
  return r;
}

namespace {
// A (stage index, report) list through an archive, as two plain vectors.
template <class Archive, class Report>
void stage_reports(Archive& ar, std::vector<std::pair<std::size_t, Report>>& list) {
  std::vector<std::size_t> stages;
  std::vector<Report> reports;
  for (const auto& [i, r] : list) {
    stages.push_back(i);
    reports.push_back(r);
  }
  ar(checkpoint::pod(stages), checkpoint::pod(reports));
  list.clear();
  for (std::size_t k = 0; k < stages.size(); ++k) list.emplace_back(stages[k], reports[k]);
}
}  // namespace

template <class Archive>
void QuasiStaticDriver::state(Archive& ar) {
  using checkpoint::pod;
  int phase = static_cast<int>(phase_);
  std::vector<std::uint8_t> stalled(outcome_.stalled.begin(), outcome_.stalled.end());
  bool control = control_.has_value();
  ar(phase, si_, t0_, control, checkpoint::bytes(state_), v_, stage_fraction_);
  if constexpr (Archive::is_loading::value) {
    if (si_ >= cfg_.load_path.stages.size())
      throw std::runtime_error("the checkpoint's stage is not in the model file");
    control_.reset();
    if (control) control_.emplace(stage(), 0.0, 0.0, 0.0);  // its state follows
  }
  if (control) ar(*control_);
  bool creep = creep_.has_value();
  ar(creep);
  if constexpr (Archive::is_loading::value) {
    creep_.reset();
    if (creep) creep_.emplace(stage());  // its state follows
  }
  if (creep) ar(*creep_);
  bool corrosion = corrosion_.has_value();
  ar(corrosion);
  if constexpr (Archive::is_loading::value) {
    corrosion_.reset();
    if (corrosion) corrosion_.emplace(stage(), *cfg_.corrosion);  // its state follows
  }
  if (corrosion) ar(*corrosion_);
  stage_reports(ar, outcome_.corrosion);
  stage_reports(ar, outcome_.creep);
  ar(good_, resume_at_, stop_);
  ar(outcome_.exit_code, outcome_.status, outcome_.peak, outcome_.trough, pod(stalled),
     outcome_.implicit_start);
  phase_ = static_cast<Phase>(phase);
  outcome_.stalled.assign(stalled.begin(), stalled.end());
}

void QuasiStaticDriver::save(checkpoint::OutArchive& ar) const {
  const_cast<QuasiStaticDriver*>(this)->state(ar);  // saving only reads
}

void QuasiStaticDriver::load(checkpoint::InArchive& ar) {
  state(ar);
}

}  // namespace vorodec::app
