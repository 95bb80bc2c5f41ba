// [solver], [loading] and [output].
#include <cmath>

#include "sections.hpp"

namespace vorodec::io {

namespace {

// gravity = [gx, gy] in m/s^2.
void read_gravity(TomlSection& s, const toml::node& g, model::Point& gravity) {
  const toml::array* a = g.as_array();
  if (!a || a->size() != 2 || !(*a)[0].is_number() || !(*a)[1].is_number())
    s.fail_at(&g, "gravity", "must be an array of two numbers [gx, gy] in m/s^2");
  gravity = {(*a)[0].value<double>().value(), (*a)[1].value<double>().value()};
  if (!std::isfinite(gravity.x) || !std::isfinite(gravity.y))
    s.fail_at(&g, "gravity", "must hold finite numbers only");
}

}  // namespace

void read_solver_table(TomlSection& top, ModelConfig& cfg) {
  if (!top.has("solver")) {
    cfg.max_steps = 20'000'000;
    return;
  }
  TomlSection s = top.sub("solver");
  cfg.solver.local_damping = s.non_negative("local_damping", 0.8);
  if (cfg.solver.local_damping >= 1) s.fail("local_damping", "must be < 1");
  cfg.solver.safety_factor = s.positive("safety_factor", 0.8);
  if (cfg.solver.safety_factor > 1) s.fail("safety_factor", "must be <= 1");
  cfg.solver.time_step = s.non_negative("time_step", 0.0);
  if (s.has("fixed_time_step")) {
    cfg.solver.fixed_time_step = s.positive("fixed_time_step", laws::required);
    if (cfg.solver.time_step > 0)
      s.fail("fixed_time_step",
             "cannot be combined with 'time_step' (density scaling): give one of them");
  }
  cfg.max_steps = s.integer("max_steps", 20'000'000, 1);
  cfg.solver.max_detection_interval =
      static_cast<int>(s.integer("max_detection_interval", 200, 1, kMaxInt));
  if (const toml::node* g = s.node("gravity")) read_gravity(s, *g, cfg.solver.gravity);
  s.finish();
}

void read_loading_table(TomlSection& top, ModelConfig& cfg) {
  if (!top.has("loading")) return;
  TomlSection l = top.sub("loading");
  cfg.load_path.confining_stress = l.non_negative("confining_stress", 0.0);
  cfg.load_path.confining_ramp_time = l.non_negative("confining_ramp_time", 0.0);
  if (cfg.load_path.confining_ramp_time > 0 && cfg.load_path.confining_stress == 0)
    l.fail("confining_ramp_time", "ramps the confinement: give confining_stress too");
  const std::string top_only = "top";
  const std::string platens = l.string("platens", &top_only);
  if (platens != "top" && platens != "both")
    l.fail("platens", "must be \"top\" or \"both\" (got \"" + platens + "\")");
  cfg.load_path.both_platens = platens == "both";
  const std::string stress = "stress";
  const std::string sides = l.string("sides", &stress);
  if (sides == "roller" || sides == "fixed") {
    cfg.load_path.sides =
        sides == "roller" ? loading::SideSupport::roller : loading::SideSupport::fixed;
    if (cfg.load_path.confining_stress != 0)
      l.fail("sides", "a supported side carries no confining_stress: remove it, or use \"stress\"");
    if (cfg.deformable.enabled)
      l.fail("sides",
             "roller and fixed sides hold rigid blocks only ([blocks] deformable = false)");
  } else if (sides != "stress") {
    l.fail("sides", "must be \"stress\", \"roller\" or \"fixed\" (got \"" + sides + "\")");
  }
  l.finish();
}

void read_output_table(TomlSection& top, ModelConfig& cfg) {
  if (!top.has("output")) return;
  TomlSection o = top.sub("output");
  cfg.output.history_steps = o.integer("history_steps", 200, 1);
  cfg.output.vtk_steps = o.integer("vtk_steps", 20000, 1);
  if (o.has("damage_grid_cell"))
    cfg.output.damage_grid_cell = o.positive("damage_grid_cell", laws::required);
  cfg.output.checkpoint_steps = o.integer("checkpoint_steps", 0, 0);
  cfg.output.checkpoint_wall_time = o.non_negative("checkpoint_wall_time", 600.0);
  if (o.has("ae_radius")) cfg.output.ae_radius = o.positive("ae_radius", laws::required);
  if (o.has("ae_shear_wave_speed"))
    cfg.output.ae_shear_wave_speed = o.positive("ae_shear_wave_speed", laws::required);
  o.finish();
}

}  // namespace vorodec::io
