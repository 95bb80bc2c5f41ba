// The [[stage]] tables: each stage's control (platen velocity, axial stress, stress rate, a stage
// mode's such as creep or corrosion, or a cyclic block of stages), its end conditions and an
// implicit start; and the stage modes' own top-level tables.
#include <fmt/format.h>

#include <algorithm>
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
// loaded from rest by compression (drivers/implicit_start).
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
  if (cfg.load_path.confining_ramp_time > 0)
    sec.fail("implicit_start",
             "brings the confinement on statically: leave out loading.confining_ramp_time");
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

// The keys of the stage's `control` (any but "cyclic"): a plain control's here, a mode's by the
// mode's own reader.
void read_control(TomlSection& sec, const std::string& control, loading::Stage& st,
                  const ModelConfig& cfg, std::span<const StageModeKeys> modes) {
  if (control == "platen_velocity") {
    st.control = loading::Control::platen_velocity;
    st.platen_velocity = sec.number("platen_velocity", laws::required);
    if (sec.has("adaptive_velocity"))
      st.adaptive = read_adaptive(sec.sub("adaptive_velocity"), st.platen_velocity);
  } else if (control == "axial_stress") {
    st.control = loading::Control::axial_stress;
    st.target_stress = sec.non_negative("target_stress", laws::required);
    st.platen_velocity = sec.positive("platen_velocity", 0.05);  // servo's speed cap
  } else if (control == "stress_rate") {
    st.control = loading::Control::stress_rate;
    st.stress_rate = sec.number("stress_rate", laws::required);
    if (st.stress_rate == 0) sec.fail("stress_rate", "must not be 0");
    st.platen_velocity = sec.positive("platen_velocity", 0.05);  // servo's speed cap
  } else {
    const auto mode = std::find_if(modes.begin(), modes.end(),
                                   [&](const StageModeKeys& m) { return control == m.control; });
    if (mode == modes.end()) {
      std::string names = "\"platen_velocity\", \"axial_stress\", \"stress_rate\"";
      for (const StageModeKeys& m : modes) names += fmt::format(", \"{}\"", m.control);
      sec.fail("control", fmt::format("must be {} or \"cyclic\" (got \"{}\")", names, control));
    }
    st.mode = mode->control;
    st.mode_settings = mode->read_stage(sec, st, cfg);
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
  if (st.mode.empty())  // a mode's stage ends as its reader says
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
  if (st.mode.empty() && st.control == loading::Control::axial_stress)
    st.end.stress = st.target_stress;
}

// One [[stage]] table: a single stage, or a cyclic block expanded into its stages.
void read_stage(TomlSection sec, std::size_t index, std::vector<loading::Stage>& stages,
                ModelConfig& cfg, std::span<const StageModeKeys> modes) {
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
  read_control(sec, control, st, cfg, modes);
  st.ramp_time = sec.non_negative("ramp_time", 0.0);
  read_end(sec, st);
  read_implicit_start(sec, st, index == 0 && stages.empty(), cfg);
  sec.finish();
  stages.push_back(st);
}

}  // namespace

void read_load_path(TomlSection& top, ModelConfig& cfg, const ModelFileKeys& keys) {
  for (const StageModeKeys& m : keys.modes)
    if (m.table && top.has(m.table)) {
      TomlSection table = top.sub(m.table);
      cfg.tables[m.table] = m.read_table(table, top, cfg);
      table.finish();
    }
  for (const DriverKeys& d : keys.drivers)
    if (top.has(d.table)) {
      if (top.has("stage"))
        top.fail("stage", fmt::format("a [{}] test is its own load path: leave out the [[stage]] "
                                      "tables",
                                      d.table));
      TomlSection table = top.sub(d.table);
      cfg.tables[d.table] = d.read_table(table, top, cfg);
      table.finish();
      return;
    }
  const toml::node* stages = top.node("stage");
  if (!stages || !stages->is_array_of_tables())
    top.fail("stage", "at least one [[stage]] table (or a [shpb] test) is required");
  const toml::array& list = *stages->as_array();
  for (std::size_t i = 0; i < list.size(); ++i)
    read_stage(TomlSection(*list[i].as_table(), fmt::format("stage[{}]", i), top.file()), i,
               cfg.load_path.stages, cfg, keys.modes);
}

}  // namespace vorodec::io
