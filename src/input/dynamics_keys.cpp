// [quiet_boundary]: viscous sides and an input pulse (the pressure bars' [shpb] is their driver's,
// src/drivers/shpb_driver.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <tuple>
#include <utility>

#include "sections.hpp"

namespace vorodec::io {

namespace {

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
  const auto lateral = [](loading::Side s) {
    return s == loading::Side::left || s == loading::Side::right;
  };
  if (cfg.load_path.sides != loading::SideSupport::stress &&
      (std::any_of(qb.sides.begin(), qb.sides.end(), lateral) ||
       (qb.input_side && lateral(*qb.input_side))))
    q.fail("sides", "the left and right sides are supported ([loading] sides): not viscous too");
  q.finish();
  return qb;
}

}  // namespace

void read_quiet_boundary_table(TomlSection& top, ModelConfig& cfg) {
  if (top.has("quiet_boundary"))
    cfg.quiet_boundary = read_quiet_boundary(top.sub("quiet_boundary"), cfg);
}

}  // namespace vorodec::io
