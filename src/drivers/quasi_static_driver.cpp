#include "quasi_static_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/engine/observer.hpp"
#include "vorodec/solver/elastic_response.hpp"

namespace vorodec::run {

// A member added to the driver is either state a checkpoint carries (save and load it in
// QuasiStaticDriver::state) or comes again from the model file or the loaded state (say so there);
// then update these sizes.
static_assert(sizeof(QuasiStaticDriver) == 816, "QuasiStaticDriver changed: see state()");
static_assert(sizeof(DriverOutcome) == 96, "DriverOutcome changed: see state()");
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
  const laws::NominalStiffness k =
      laws::find_law(cfg.joints.name)->nominal_stiffness(cfg.joints.params);
  const auto speed = [&](double given, double stiffness) {
    return given > 0 ? given : std::sqrt(stiffness * d / cfg.density);
  };
  std::vector<loading::BoundaryEdge> edges;
  for (const loading::Side s : q.sides) {
    const auto e = loading::outline_edges(m, s);
    edges.insert(edges.end(), e.begin(), e.end());
  }
  loading::QuietBoundary quiet(
      edges, {cfg.density, speed(q.p_wave_speed, k.normal), speed(q.s_wave_speed, k.shear)});
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

// The blocks with an edge on the lateral sides (each once, in block order).
std::vector<std::uint32_t> side_blocks(const loading::SpecimenBoundary& boundary) {
  std::vector<std::uint32_t> blocks;
  for (const loading::BoundaryEdge& e : boundary.lateral_edges()) blocks.push_back(e.block);
  std::sort(blocks.begin(), blocks.end());
  blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  return blocks;
}

// The supports' reaction, between the step's contact forces and its integration: each side
// block's load cancels its contact force across the side and its moment (and along the side
// too for fixed sides), so it keeps a zero velocity there and does not turn.
void hold_sides(model::Model& m, const solver::Solver& s, const std::vector<std::uint32_t>& blocks,
                bool fixed) {
  auto& bl = m.blocks;
  const model::Point g = s.settings().gravity;
  for (const std::uint32_t b : blocks) {
    const model::Point f = s.contact_force(b);
    bl.fx[b] = -(f.x + bl.gravity_mass[b] * g.x);
    bl.fy[b] = fixed ? -(f.y + bl.gravity_mass[b] * g.y) : 0.0;
    bl.moment[b] = -s.contact_moment(b);
    bl.vx[b] = bl.omega[b] = 0.0;
    if (fixed) bl.vy[b] = 0.0;
  }
}

}  // namespace

QuasiStaticDriver::QuasiStaticDriver(const DriverContext& c)
    : cfg_(c.cfg),
      model_(c.model),
      solver_(c.solver),
      boundary_(c.boundary),
      specimen_(c.specimen),
      limit_{c.step_limit, c.limit_from_option},
      modes_(make_stage_modes(c)),
      state_(measure::measure_specimen(c.model, c.boundary, c.solver)) {
  outcome_.stalled.assign(cfg_.load_path.stages.size(), false);
  if (cfg_.load_path.stages.empty()) phase_ = Phase::done;
  if (cfg_.quiet_boundary) quiet_.emplace(make_quiet_boundary(*cfg_.quiet_boundary, cfg_, model_));
  if (cfg_.load_path.sides != loading::SideSupport::stress) {
    const bool fixed = cfg_.load_path.sides == loading::SideSupport::fixed;
    solver_.set_face_control([this, fixed, blocks = side_blocks(boundary_)] {
      hold_sides(model_, solver_, blocks, fixed);
    });
  }
  if (cfg_.in_situ) {
    in_situ_ = loading::resolved(*cfg_.in_situ, model_);
    in_situ_mid_xx_ = in_situ_->at(loading::specimen_top(model_) - 0.5 * boundary_.height()).xx;
  }
}

RunView QuasiStaticDriver::view() const {
  return {model_,    solver_,
          specimen_, state_,
          v_,        static_cast<int>(si_),
          nullptr,   modes_.empty() ? nullptr : static_cast<const ExtraColumns*>(this)};
}

StageMode* QuasiStaticDriver::mode_of(const loading::Stage& stage) const {
  for (const auto& m : modes_)
    if (m->runs(stage)) return m.get();
  return nullptr;
}

std::vector<std::string> QuasiStaticDriver::column_names() const {
  std::vector<std::string> names;
  for (const auto& m : modes_) {
    const std::vector<std::string> own = m->column_names();
    names.insert(names.end(), own.begin(), own.end());
  }
  return names;
}

void QuasiStaticDriver::column_values(std::vector<double>& row) const {
  for (const auto& m : modes_) m->column_values(row);
}

void QuasiStaticDriver::summarise(io::Json& summary) const {
  if (implicit_start_) summary["implicit_start"] = implicit_start_json(*implicit_start_);
  for (const auto& m : modes_) m->summarise(summary);
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
    mark_unstable(outcome_, e.what());
    if (mode_ && phase_ == Phase::stepping) {
      const std::string status = mode_->unstable(context(), e.what());
      if (!status.empty()) outcome_.status = status;
      mode_ = nullptr;
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
  mode_ = mode_of(st);
  if (mode_) mode_->begin_stage(context());
  // After a stage whose mode set its own time step (creep), the model file's again.
  if (!(mode_ && mode_->sets_time_step()) && solver_.scaling_time_step() != cfg_.solver.time_step)
    solver_.rescale_time_step(cfg_.solver.time_step);
  observers.sample(view(), {st.name + ":start", true, false});
  if (st.implicit_start) {
    try {
      implicit_start_ =
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
  if (limit_.reached(solver_.steps(), outcome_)) {
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
  boundary_.set_platen_velocity(model_, v_, cfg_.load_path.both_platens);
  if (quiet_) quiet_->clear_loads(model_);
  // The lateral stress: the in-situ field's (its horizontal stress at mid-height stands for it in
  // the end conditions), or the load path's confinement.
  const double confinement =
      in_situ_ ? in_situ_mid_xx_ : cfg_.load_path.confinement_at(solver_.time());
  // Supported sides take their reaction inside the step (hold_sides).
  if (cfg_.load_path.sides == loading::SideSupport::stress) {
    if (in_situ_)
      boundary_.apply_stress(model_, *in_situ_);
    else
      boundary_.apply_confinement(model_, confinement);
  }
  if (quiet_) quiet_->apply(model_, solver_.time());
  solver_.step();
  state_ = measure::measure_specimen(model_, boundary_, solver_);
  good_.check(solver_, model_);
  track_extremes(outcome_, state_.axial_stress);
  const Due d = due(solver_.steps(), cfg_.output.history_steps, cfg_.output.vtk_steps);
  if (d.row || d.frame) observers.sample(view(), {st.name, d.row, d.frame});
  const loading::StageOutcome outcome = control.judge(
      {solver_.time() - t0_, state_.axial_stress, state_.axial_strain, d.row, confinement});
  stage_fraction_ = std::max(stage_fraction_, control.fraction());
  if (mode_) {
    const ModeVerdict verdict = mode_->after_step(context(), state_);
    if (!verdict.sample.empty()) observers.sample(view(), {st.name + verdict.sample, true, false});
    if (!verdict.status.empty()) outcome_.status = verdict.status;
    stop_ = stop_ || verdict.stop_run;
    if (verdict.end_stage) {
      phase_ = Phase::stage_end;
      return;
    }
  }
  if (outcome == loading::StageOutcome::stalled) {
    outcome_.stalled[si_] = true;
    resume_at_ = st.block_end;
  }
  if (outcome != loading::StageOutcome::running) phase_ = Phase::stage_end;
}

void QuasiStaticDriver::end_stage(Observers& observers) {
  const loading::Stage& st = stage();
  const std::string label = st.name + (outcome_.stalled[si_] ? ":stalled" : ":end");
  if (mode_) mode_->end_stage(context());
  mode_ = nullptr;
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
  if (mode_ && mode_->progress(context(), r)) return r;
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
  for (const auto& m : modes_) {
    if constexpr (Archive::is_loading::value)
      m->load(ar, stage());
    else
      m->save(ar);
  }
  ar(good_, resume_at_, stop_);
  ar(outcome_.exit_code, outcome_.status, outcome_.peak, outcome_.trough, pod(stalled),
     implicit_start_);
  phase_ = static_cast<Phase>(phase);
  // The current stage's mode, as start_stage found it (none once the stage has ended).
  if constexpr (Archive::is_loading::value)
    mode_ = phase_ == Phase::stepping ? mode_of(stage()) : nullptr;
  outcome_.stalled.assign(stalled.begin(), stalled.end());
}

void QuasiStaticDriver::save(checkpoint::OutArchive& ar) const {
  const_cast<QuasiStaticDriver*>(this)->state(ar);  // saving only reads
}

void QuasiStaticDriver::load(checkpoint::InArchive& ar) {
  state(ar);
}

}  // namespace vorodec::run
