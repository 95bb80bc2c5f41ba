// The dynamic tests: [shpb] (a split Hopkinson pressure bar, a load path of its own) and
// [quiet_boundary] (viscous sides and an input pulse).
#include <fmt/format.h>

#include <algorithm>
#include <tuple>
#include <utility>

#include "sections.hpp"

namespace vorodec::io {

namespace {

// [shpb.incident_bar] or [shpb.transmitted_bar]; the transmitted bar takes `like`'s (the incident
// bar's) diameter, E and density unless it gives its own.
loading::BarProperties read_bar(TomlSection b, const loading::BarProperties* like,
                                std::vector<double>& gauges) {
  loading::BarProperties p;
  p.length = b.positive("length", laws::required);
  p.width = b.positive("diameter", like ? like->width : laws::required);
  p.youngs_modulus = b.positive("E", like ? like->youngs_modulus : laws::required);
  p.density = b.positive("density", like ? like->density : laws::required);
  const std::string free_end = "free";
  const std::string end = b.string("far_end", &free_end);
  if (end != "free" && end != "quiet")
    b.fail("far_end", "\"free\" or \"quiet\" (viscous, non-reflecting)");
  p.quiet_far_end = end == "quiet";
  gauges = b.numbers("gauges");
  for (const double x : gauges)
    if (!(x > 0 && x < p.length))
      b.fail("gauges", fmt::format("a gauge at {} m is outside its bar (0, {} m) from the face", x,
                                   p.length));
  b.finish();
  return p;
}

// bars = "blocks": the bars built from blocks of bar_block_length.
void read_block_bars(TomlSection& sec, ShpbConfig& s) {
  s.bar_block_length = sec.positive("bar_block_length", 0.1 * s.incident.width);
  if (!s.incident.quiet_far_end)
    sec.sub("incident_bar")
        .fail("far_end",
              "with bars = \"blocks\" the striker's pulse enters through the incident "
              "bar's far end, which absorbs what returns: far_end = \"quiet\"");
  if (s.transmitted.length < 2.0 * s.bar_block_length)
    sec.fail("bar_block_length",
             fmt::format("{} m: each bar needs at least two blocks", s.bar_block_length));
}

// [shpb] with [shpb.incident_bar] and [shpb.transmitted_bar].
ShpbConfig read_shpb(TomlSection sec) {
  ShpbConfig s;
  s.incident = read_bar(sec.sub("incident_bar"), nullptr, s.incident_gauges);
  s.transmitted = read_bar(sec.sub("transmitted_bar"), &s.incident, s.transmitted_gauges);
  s.striker_length = sec.positive("striker_length", laws::required);
  s.striker_velocity = sec.positive("striker_velocity", laws::required);
  const double pulse = 2.0 * s.striker_length / s.incident.wave_speed();
  if (2.0 * s.striker_length >= s.incident.length)
    sec.fail("striker_length",
             fmt::format("the pulse (2 x striker_length = {} m) is longer than the incident bar "
                         "({} m): incident and reflected waves overlap everywhere on it",
                         2.0 * s.striker_length, s.incident.length));
  for (const double x : s.incident_gauges)
    if (x < s.striker_length)
      sec.fail("striker_length",
               fmt::format("the incident gauge at {} m is closer to the face than half the "
                           "pulse ({} m): its incident and reflected waves overlap",
                           x, s.striker_length));
  s.rise_time = sec.non_negative("rise_time", 0.0);
  if (2.0 * s.rise_time > pulse)
    sec.fail("rise_time", fmt::format("the rise and the fall ({} s each) take longer than the "
                                      "pulse (2 x striker_length / c0 = {} s)",
                                      s.rise_time, pulse));
  const std::string exact = "exact";
  const std::string bars = sec.string("bars", &exact);
  if (bars != "exact" && bars != "blocks")
    sec.fail("bars", "\"exact\" (1D elastic bars) or \"blocks\" (bars built from blocks)");
  s.block_bars = bars == "blocks";
  if (s.block_bars)
    read_block_bars(sec, s);
  else if (sec.has("bar_block_length"))
    sec.fail("bar_block_length", "only with bars = \"blocks\"");
  s.duration = sec.positive("duration", 2.0 * pulse);
  s.record_interval = sec.positive("record_interval", pulse / 1000.0);
  s.equilibrium_tolerance = sec.positive("equilibrium_tolerance", 0.05);
  sec.finish();
  return s;
}

loading::Side side_named(TomlSection& q, const toml::node* where, std::string_view key,
                         const std::string& name) {
  const std::pair<const char*, loading::Side> names[] = {{"left", loading::Side::left},
                                                         {"right", loading::Side::right},
                                                         {"bottom", loading::Side::bottom},
                                                         {"top", loading::Side::top}};
  for (const auto& [n, s] : names)
    if (name == n) return s;
  q.fail_at(where, key,
            fmt::format("'{}' is not a side: \"left\", \"right\", \"bottom\" or \"top\"", name));
}

// input_side: a half-sine particle-velocity pulse enters through it.
void read_input_pulse(TomlSection& q, QuietBoundaryConfig& qb) {
  qb.input_side =
      side_named(q, q.node("input_side"), "input_side", q.string("input_side", nullptr));
  if (std::find(qb.sides.begin(), qb.sides.end(), *qb.input_side) != qb.sides.end())
    q.fail("input_side", "the input side absorbs as well: leave it out of 'sides'");
  qb.input_velocity = q.number("input_velocity", laws::required);
  qb.input_duration = q.positive("input_duration", laws::required);
  const std::string normal = "normal";
  const std::string dir = q.string("input_direction", &normal);
  if (dir != "normal" && dir != "shear")
    q.fail("input_direction", "\"normal\" (into the side) or \"shear\" (along it)");
  qb.input_shear = dir == "shear";
}

QuietBoundaryConfig read_quiet_boundary(TomlSection q, const ModelConfig& cfg) {
  QuietBoundaryConfig qb;
  if (const toml::node* sides = q.node("sides")) {
    if (!sides->is_array()) q.fail("sides", "an array of sides, e.g. [\"left\", \"right\"]");
    for (const toml::node& e : *sides->as_array()) {
      if (!e.is_string()) q.fail_at(&e, "sides", "each side is a string, e.g. \"left\"");
      qb.sides.push_back(side_named(q, &e, "sides", *e.value<std::string>()));
    }
  }
  const laws::NominalStiffness springs = nominal_stiffness(cfg.joints);
  for (const auto& [key, spring, stiffness, speed] :
       {std::tuple{"p_wave_speed", "normal", springs.normal, &qb.p_wave_speed},
        std::tuple{"s_wave_speed", "shear", springs.shear, &qb.s_wave_speed}}) {
    if (q.has(key))
      *speed = q.positive(key, laws::required);
    else if (!(stiffness > 0))
      q.fail(key, fmt::format("required: the joints' law '{}' has no {} spring to derive it from",
                              cfg.joints.name, spring));
  }
  if (q.has("input_side")) read_input_pulse(q, qb);
  if (qb.sides.empty() && !qb.input_side)
    q.fail("sides", "name the absorbing sides (or an input_side)");
  if (cfg.deformable.enabled)
    q.fail("sides", "quiet boundaries need rigid blocks ([blocks] deformable = false)");
  if (cfg.shpb) q.fail("sides", "a [shpb] test's bars are its boundaries: no quiet boundary");
  q.finish();
  return qb;
}

}  // namespace

void read_shpb_table(TomlSection& top, ModelConfig& cfg) {
  if (top.has("stage"))
    top.fail("stage", "a [shpb] test is its own load path: leave out the [[stage]] tables");
  if (cfg.load_path.confining_stress > 0)
    top.fail("loading", "a [shpb] test has no confinement: leave out confining_stress");
  if (cfg.solver.time_step > 0)
    TomlSection(*top.table()["solver"].as_table(), "solver", top.file())
        .fail("time_step", "density scaling would change the inertia a [shpb] test measures");
  cfg.shpb = read_shpb(top.sub("shpb"));
}

void read_quiet_boundary_table(TomlSection& top, ModelConfig& cfg) {
  if (top.has("quiet_boundary"))
    cfg.quiet_boundary = read_quiet_boundary(top.sub("quiet_boundary"), cfg);
}

}  // namespace vorodec::io
