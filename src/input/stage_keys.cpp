// The [[stage]] tables: each stage's control (platen velocity, axial stress, stress rate, creep,
// corrosion, or a cyclic block of stages), its end conditions and an implicit start.
#include <fmt/format.h>

#include <cmath>

#include "sections.hpp"

namespace vorodec::io {

namespace {

loading::CyclicBlock read_cycles(TomlSection& sec, const std::string& name) {
  loading::CyclicBlock b;
  b.name = name;
  if (sec.has("upper_stresses")) {
    b.upper_stresses = sec.numbers("upper_stresses");
    for (double u : b.upper_stresses)
      if (!(u > 0)) sec.fail("upper_stresses", "every upper stress must be > 0 Pa");
  } else {
    const double peak = sec.positive("reference_peak", laws::required);
    const double first = sec.positive("first_upper_fraction", laws::required);
    const double step = sec.non_negative("upper_increment_fraction", laws::required);
    const long n = sec.integer("cycles", 0, 1, kMaxCycles);
    if (n < 1) sec.fail("cycles", "required key is missing (number of cycles, >= 1)");
    for (long k = 0; k < n; ++k)
      b.upper_stresses.push_back(peak * (first + step * static_cast<double>(k)));
    if (!std::isfinite(b.upper_stresses.back()))
      sec.fail("reference_peak", "the last cycle's upper stress overflows (is not finite)");
  }
  b.lower_stress = sec.non_negative("lower_stress", 0.0);
  for (double u : b.upper_stresses)
    if (u <= b.lower_stress) sec.fail("lower_stress", "must lie below every upper stress");
  b.loading_velocity = sec.positive("platen_velocity", laws::required);
  b.unloading_rate = sec.positive("unloading_rate", laws::required);
  b.ramp_time = sec.non_negative("ramp_time", 0.0);
  b.servo_velocity_cap = sec.positive("servo_velocity_cap", 0.05);
  return b;
}

// A velocity stage's adaptive_velocity table; v0 is the stage's platen_velocity (starting speed).
loading::AdaptiveVelocity read_adaptive(TomlSection sec, double v0) {
  loading::AdaptiveVelocity a;
  a.enabled = true;
  a.target_ratio = sec.positive("target_ratio", laws::required);
  a.min_velocity = sec.positive("min_velocity", laws::required);
  a.max_velocity = sec.positive("max_velocity", laws::required);
  if (a.max_velocity < a.min_velocity)
    sec.fail("max_velocity", fmt::format("must be >= min_velocity ({} m/s)", a.min_velocity));
  if (v0 < a.min_velocity || v0 > a.max_velocity)
    sec.fail("min_velocity",
             fmt::format("the stage's platen_velocity ({} m/s, the starting speed) must lie "
                         "between min_velocity and max_velocity",
                         v0));
  a.interval_steps = sec.integer("interval_steps", 500, 1);
  a.max_change = sec.number("max_change", 1.25);
  if (!(a.max_change > 1))
    sec.fail("max_change", fmt::format("must be > 1 (got {})", a.max_change));
  sec.finish();
  return a;
}

// stage key implicit_start: the first velocity stage of a rigid-block model without gravity,
// loaded from rest by compression (app/implicit_start).
void read_implicit_start(TomlSection& sec, loading::Stage& st, bool first, ModelConfig& cfg) {
  st.implicit_start = sec.boolean("implicit_start", false);
  if (!st.implicit_start) {
    for (const char* key : {"implicit_start_fraction", "implicit_start_increments"})
      if (sec.has(key)) sec.fail(key, "needs implicit_start = true");
    return;
  }
  if (!first) sec.fail("implicit_start", "only the first stage can start implicitly (from rest)");
  if (st.control != loading::Control::platen_velocity || st.platen_velocity <= 0)
    sec.fail("implicit_start", "needs a compressing velocity stage (platen_velocity > 0)");
  if (cfg.solver.gravity.x != 0 || cfg.solver.gravity.y != 0)
    sec.fail("implicit_start", "needs [solver] gravity = [0, 0]");
  if (cfg.deformable.enabled) sec.fail("implicit_start", "needs rigid blocks");
  st.implicit_start_fraction = sec.positive("implicit_start_fraction", 0.9);
  if (st.implicit_start_fraction > 1)
    sec.fail("implicit_start_fraction",
             fmt::format("must be in (0, 1] (got {})", st.implicit_start_fraction));
  st.implicit_start_increments =
      static_cast<int>(sec.integer("implicit_start_increments", 10, 1, kMaxImplicitIncrements));
  const toml::source_region& at = sec.table().get("implicit_start")->source();
  // A value from --set or a batch case was parsed from text: it has no file or line.
  cfg.implicit_start_where =
      at.path
          ? fmt::format("{}:{}: key '{}'", *at.path, at.begin.line, sec.key_path("implicit_start"))
          : fmt::format("{}: --set key '{}'", sec.file(), sec.key_path("implicit_start"));
}

bool viscous_law(const LawChoice& c) {
  return laws::find_law(c.name)->make(c.params, 0)->viscous();
}
bool viscous_joints(const ModelConfig& cfg) {
  if (viscous_law(cfg.joints) || (cfg.joint_mix && viscous_law(cfg.joint_mix->law))) return true;
  if (!cfg.grains) return false;
  const GrainConfig& g = *cfg.grains;
  if (viscous_law(g.transgranular)) return true;
  for (const auto& in : g.inside)
    if (in && viscous_law(*in)) return true;
  for (const auto& p : g.pairs)
    if (viscous_law(p.law)) return true;
  return false;
}

// control = "creep": the servo holds sigma1 = confining_stress + deviatoric_stress for a duration
// (s) or duration_days, at the creep step (loading::CreepSettings).
void read_creep(TomlSection& sec, loading::Stage& st, const ModelConfig& cfg) {
  st.control = loading::Control::axial_stress;
  st.creep.enabled = true;
  st.target_stress =
      cfg.load_path.confining_stress + sec.positive("deviatoric_stress", laws::required);
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
  st.creep.step_factor = sec.positive("creep_step_factor", st.creep.step_factor);
  if (sec.has("creep_time_step")) st.creep.time_step = sec.positive("creep_time_step", 0);
  st.creep.target_ratio = sec.positive("creep_target_ratio", st.creep.target_ratio);
  st.creep.interval_steps = sec.integer("creep_interval_steps", st.creep.interval_steps, 1);
  if (cfg.deformable.enabled)
    sec.fail("control", "creep stages need rigid blocks ([blocks] deformable = false)");
  if (cfg.solver.fixed_time_step > 0)
    sec.fail("control", "creep stages set the step themselves: remove [solver] fixed_time_step");
  if (st.creep.time_step == 0 && !viscous_joints(cfg))
    sec.fail("control",
             fmt::format("a creep stage sizes its step from the contacts' dashpots, and law '{}' "
                         "has none: use law = \"burgers\" or give creep_time_step (s)",
                         cfg.joints.name));
}

// control = "corrosion": the servo holds sigma1 = sigma3 + rs (sf - sigma3) while the corrosion
// layers of [corrosion] run (loading::CorrosionSettings), until collapse or the duration.
void read_corrosion_stage(TomlSection& sec, loading::Stage& st, const ModelConfig& cfg) {
  if (!cfg.corrosion)
    sec.fail("control", "a corrosion stage needs a [corrosion] table (the layers' constants)");
  st.control = loading::Control::axial_stress;
  loading::CorrosionSettings& c = st.corrosion;
  c.enabled = true;
  c.driving_stress_ratio = sec.positive("driving_stress_ratio", laws::required);
  if (c.driving_stress_ratio >= 1)
    sec.fail("driving_stress_ratio",
             fmt::format("must be in (0, 1) (got {})", c.driving_stress_ratio));
  const double s3 = cfg.load_path.confining_stress;
  c.peak_stress = sec.positive("peak_stress", laws::required);
  if (c.peak_stress <= s3)
    sec.fail("peak_stress",
             fmt::format("must exceed the confining stress {} Pa (got {})", s3, c.peak_stress));
  st.target_stress = s3 + c.driving_stress_ratio * (c.peak_stress - s3);
  st.platen_velocity = sec.positive("platen_velocity", 0.05);  // servo's speed cap
  c.steps_per_failure = sec.number("steps_per_failure", c.steps_per_failure);
  if (!(c.steps_per_failure >= 1))
    sec.fail("steps_per_failure", fmt::format("n_c must be >= 1 (got {})", c.steps_per_failure));
  const std::string held = "held";
  const std::string ttf = sec.string("time_to_failure", &held);
  if (ttf != "held" && ttf != "frozen")
    sec.fail("time_to_failure",
             fmt::format("must be \"held\" (forces held, integrated) or "
                         "\"frozen\" (the rate frozen, [Potyondy2007]) (got \"{}\")",
                         ttf));
  c.frozen_rate = ttf == "frozen";
  c.equilibrium_ratio = sec.positive("equilibrium_ratio", c.equilibrium_ratio);
  c.check_interval = sec.integer("check_interval", c.check_interval, 1);
  c.max_equilibrium_steps = sec.integer("max_equilibrium_steps", c.max_equilibrium_steps, 1);
  int given = 0;
  for (const auto& [key, unit] : {std::pair{"duration", 1.0}, std::pair{"duration_days", 86400.0},
                                  std::pair{"duration_years", 365.25 * 86400.0}})
    if (sec.has(key)) {
      if (++given > 1)
        sec.fail(key, "give at most one of duration (s), duration_days and duration_years");
      c.max_time = unit * sec.positive(key, laws::required);
    }
  if (sec.has("end_time")) sec.fail("end_time", "a corrosion stage ends by failure or duration");
  if (cfg.deformable.enabled)
    sec.fail("control", "corrosion stages need rigid blocks ([blocks] deformable = false)");
}

// The keys of the stage's `control` (any but "cyclic").
void read_control(TomlSection& sec, const std::string& control, loading::Stage& st,
                  const ModelConfig& cfg) {
  if (control == "platen_velocity") {
    st.control = loading::Control::platen_velocity;
    st.platen_velocity = sec.number("platen_velocity", laws::required);
    if (sec.has("adaptive_velocity"))
      st.adaptive = read_adaptive(sec.sub("adaptive_velocity"), st.platen_velocity);
  } else if (control == "axial_stress") {
    st.control = loading::Control::axial_stress;
    st.target_stress = sec.non_negative("target_stress", laws::required);
    st.platen_velocity = sec.positive("platen_velocity", 0.05);  // servo's speed cap
  } else if (control == "creep") {
    read_creep(sec, st, cfg);
  } else if (control == "corrosion") {
    read_corrosion_stage(sec, st, cfg);
  } else if (control == "stress_rate") {
    st.control = loading::Control::stress_rate;
    st.stress_rate = sec.number("stress_rate", laws::required);
    if (st.stress_rate == 0) sec.fail("stress_rate", "must not be 0");
    st.platen_velocity = sec.positive("platen_velocity", 0.05);  // servo's speed cap
  } else {
    sec.fail("control",
             fmt::format("must be \"platen_velocity\", \"axial_stress\", "
                         "\"stress_rate\", \"creep\", \"corrosion\" or \"cyclic\" (got \"{}\")",
                         control));
  }
}

// When the stage ends: end_axial_strain, end_post_peak_fraction, end_time, end_axial_stress, or
// (an axial-stress stage) once its target is held.
void read_end(TomlSection& sec, loading::Stage& st) {
  const double nan = loading::StageEnd::unset;
  st.end.axial_strain = sec.has("end_axial_strain") ? sec.number("end_axial_strain", nan) : nan;
  if (sec.has("end_post_peak_fraction")) {
    st.end.post_peak_fraction = sec.number("end_post_peak_fraction", nan);
    if (!(st.end.post_peak_fraction > 0 && st.end.post_peak_fraction < 1))
      sec.fail("end_post_peak_fraction", "must be between 0 and 1");
  }
  if (st.control != loading::Control::axial_stress || !(st.creep.enabled || st.corrosion.enabled))
    st.end.duration = sec.has("end_time") ? sec.positive("end_time", nan) : nan;
  st.end.axial_stress = sec.has("end_axial_stress") ? sec.number("end_axial_stress", nan) : nan;
  if (st.control == loading::Control::stress_rate && std::isnan(st.end.axial_stress) &&
      std::isnan(st.end.duration))
    sec.fail("end_axial_stress", "a stress_rate stage needs end_axial_stress or end_time");
  if (std::isnan(st.end.axial_strain) && std::isnan(st.end.post_peak_fraction) &&
      std::isnan(st.end.duration) && std::isnan(st.end.axial_stress) &&
      st.control == loading::Control::platen_velocity)
    sec.fail("end_axial_strain",
             "a stage needs an end condition: end_axial_strain, end_post_peak_fraction, "
             "end_axial_stress or end_time");
  // A corrosion stage holds its stress until failure: it does not end when the target is held.
  if (st.control == loading::Control::axial_stress && !st.corrosion.enabled)
    st.end.stress = st.target_stress;
}

// One [[stage]] table: a single stage, or a cyclic block expanded into its stages.
void read_stage(TomlSection sec, std::size_t index, std::vector<loading::Stage>& stages,
                ModelConfig& cfg) {
  loading::Stage st;
  const std::string fallback = fmt::format("stage {}", index + 1);
  const std::string vel = "platen_velocity";
  const std::string control = sec.string("control", &vel);
  if (control == "cyclic") {
    if (sec.has("implicit_start"))
      sec.fail("implicit_start", "needs a velocity stage, not a cyclic block");
    const std::string cycle = "cycle";
    loading::append_cycles(read_cycles(sec, sec.string("name", &cycle)), stages);
    sec.finish();
    return;
  }
  st.name = sec.string("name", &fallback);
  read_control(sec, control, st, cfg);
  st.ramp_time = sec.non_negative("ramp_time", 0.0);
  read_end(sec, st);
  read_implicit_start(sec, st, index == 0 && stages.empty(), cfg);
  sec.finish();
  stages.push_back(st);
}

}  // namespace

void read_stage_tables(TomlSection& top, ModelConfig& cfg) {
  const toml::node* stages = top.node("stage");
  if (!stages || !stages->is_array_of_tables())
    top.fail("stage", "at least one [[stage]] table (or a [shpb] test) is required");
  const toml::array& list = *stages->as_array();
  for (std::size_t i = 0; i < list.size(); ++i)
    read_stage(TomlSection(*list[i].as_table(), fmt::format("stage[{}]", i), top.file()), i,
               cfg.load_path.stages, cfg);
}

}  // namespace vorodec::io
