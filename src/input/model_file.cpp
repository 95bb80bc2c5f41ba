#include "vorodec/input/model_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "vorodec/input/override.hpp"
#include "vorodec/input/toml_section.hpp"
#include "vorodec/io/grain_file.hpp"
#include "vorodec/laws/reference.hpp"

namespace vorodec::io {

namespace {

// Limits that keep `vorodec check` and a run's set-up bounded (README.md, model file reference).
// The counts are estimated from the outline area before anything is tessellated.
constexpr double kMinLength = 1e-6;      // m, specimen dimensions and block, grain, sub-block sizes
constexpr double kMaxLength = 1e3;       // m
constexpr double kMaxBlocks = 1e6;       // blocks of a Voronoi specimen; grains; sub-blocks
constexpr double kMaxZones = 1e7;        // zones of deformable blocks, 2 x area / zone_size^2
constexpr double kMaxDamageCells = 1e6;  // area / damage_grid_cell^2
constexpr long kMaxLloydIterations = 100;
constexpr long kMaxCycles = 10'000;
constexpr long kMaxImplicitIncrements = 1'000;
constexpr long kMaxInt = std::numeric_limits<int>::max();  // keys kept in an int
// Mean Voronoi edge ~ 0.65 sqrt(area / blocks) (as src/geometry/voronoi_builder.cpp estimates).
constexpr double kPoissonEdgeFactor = 0.65;

// A length of the specimen (m): within [kMinLength, kMaxLength], so that areas, block counts and
// the tessellation's tolerances stay in double range.
double specimen_length(TomlSection& sec, std::string_view key) {
  const double v = sec.positive(key, laws::required);
  if (v < kMinLength || v > kMaxLength)
    sec.fail(key, fmt::format("must be between {:g} m and {:g} m (got {:g} m)", kMinLength,
                              kMaxLength, v));
  return v;
}

// Without throwing: a path the system refuses (too long, no permission) counts as absent.
bool file_exists(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::exists(p, ec);
}

std::string mm(double metres) {
  return fmt::format("{:.4g} mm", metres * 1e3);
}

bool in_range(const laws::ParamSpec& spec, double v) {
  return (spec.min_inclusive ? v >= spec.min : v > spec.min) && v <= spec.max;
}

// A law property: a number, or { weibull_shape = m, mean = a0 } / { weibull_shape = m, scale = l }.
model::Distribution read_property(TomlSection& sec, const laws::ParamSpec& spec) {
  const toml::node* n = sec.node(spec.key);
  if (n->is_table()) {
    if (!spec.distributable) sec.fail(spec.key, "cannot be distributed");
    TomlSection d(*n->as_table(), sec.key_path(spec.key), sec.file());
    const double m = d.positive("weibull_shape", laws::required);
    const bool has_mean = d.has("mean"), has_scale = d.has("scale");
    if (has_mean == has_scale)
      sec.fail(spec.key, "give exactly one of 'mean' (a0, the distribution's mean) and 'scale'");
    const double a = d.number(has_mean ? "mean" : "scale", laws::required);
    if (!in_range(spec, a))
      d.fail(has_mean ? "mean" : "scale",
             fmt::format("must be {} (got {})", laws::range_text(spec), a));
    d.finish();
    const model::Distribution dist = has_mean ? model::Distribution::weibull_from_mean(m, a)
                                              : model::Distribution::weibull_from_scale(m, a);
    // Gamma(1 + 1/m) overflows for m below about 0.006: the mean or the scale would be 0 or inf.
    if (!std::isfinite(dist.value) || !std::isfinite(dist.weibull_scale) ||
        (a != 0 && (dist.value == 0 || dist.weibull_scale == 0)))
      d.fail("weibull_shape", fmt::format("is too small (got {:g}): Gamma(1 + 1/m) overflows", m));
    return dist;
  }
  if (spec.unit == "bool") return model::Distribution::constant(sec.boolean(spec.key, false));
  const double v = sec.number(spec.key, laws::required);
  if (!in_range(spec, v))
    sec.fail(spec.key, fmt::format("must be {} (got {})", laws::range_text(spec), v));
  return model::Distribution::constant(v);
}

LawChoice read_law(TomlSection& sec, const std::string& default_law) {
  LawChoice choice;
  choice.name = sec.string("law", &default_law);
  const laws::LawInfo* info = laws::find_law(choice.name);
  if (!info) {
    std::string names;
    for (const auto& l : laws::law_registry()) names += fmt::format(" '{}'", l.name);
    sec.fail("law", fmt::format("unknown contact law '{}' (known:{})", choice.name, names));
  }
  for (const laws::ParamSpec& spec : info->params) {
    sec.node(spec.key);  // a known key of this law, even where absent (for "did you mean")
    if (sec.has(spec.key)) {
      choice.params.emplace(std::string(spec.key), read_property(sec, spec));
    } else if (!std::isnan(spec.default_value)) {
      choice.params.emplace(std::string(spec.key),
                            model::Distribution::constant(spec.default_value));
    } else if (!spec.optional) {
      sec.fail(spec.key,
               fmt::format("required by law '{}' ({}, {})", choice.name, spec.doc, spec.unit));
    }
  }
  return choice;
}

void read_outline(TomlSection& sec, geometry::Outline& outline) {
  const std::string rect = "rectangle";
  const std::string shape = sec.string("shape", &rect);
  if (shape == "rectangle") {
    outline.kind = geometry::OutlineKind::rectangle;
    outline.width = specimen_length(sec, "width");
    outline.height = specimen_length(sec, "height");
  } else if (shape == "disc") {
    outline.kind = geometry::OutlineKind::disc;
    outline.diameter = specimen_length(sec, "diameter");
    // A flattened Brazilian disc: flats that spread the platens' load over an arc.
    const double flat = sec.non_negative("flat_angle", 0.0);
    if (flat > 60.0) sec.fail("flat_angle", fmt::format("must be at most 60 deg (got {:g})", flat));
    outline.flat_angle = flat * std::numbers::pi / 180.0;
  } else {
    sec.fail("shape", fmt::format("must be \"rectangle\" or \"disc\" (got \"{}\")", shape));
  }
}

std::vector<Mineral> read_minerals(TomlSection& top, bool need_fractions) {
  const toml::node* n = top.node("mineral");
  if (!n || !n->is_array_of_tables())
    top.fail("mineral",
             "a grain-based specimen needs [[mineral]] tables (name, fraction, density)");
  std::vector<Mineral> minerals;
  double sum = 0;
  const toml::array& list = *n->as_array();
  for (std::size_t i = 0; i < list.size(); ++i) {
    TomlSection m(*list[i].as_table(), fmt::format("mineral[{}]", i), top.file());
    Mineral x;
    x.name = m.string("name", nullptr);
    for (const Mineral& y : minerals)
      if (y.name == x.name) m.fail("name", fmt::format("mineral '{}' is given twice", x.name));
    x.fraction =
        need_fractions || m.has("fraction") ? m.non_negative("fraction", laws::required) : 0.0;
    if (x.fraction > 1) m.fail("fraction", "must be an area fraction between 0 and 1");
    x.density = m.positive("density", laws::required);
    if (m.has("E")) x.youngs_modulus = m.positive("E", laws::required);
    if (m.has("nu")) {
      x.poisson_ratio = m.number("nu", laws::required);
      if (!(x.poisson_ratio > -1.0 && x.poisson_ratio < 0.5))
        m.fail("nu", fmt::format("must be > -1 and < 0.5 (got {})", x.poisson_ratio));
    }
    if (m.has("E") != m.has("nu"))
      m.fail(m.has("E") ? "E" : "nu", "give both E and nu, or neither");
    m.finish();
    sum += x.fraction;
    minerals.push_back(x);
  }
  if (need_fractions && std::abs(sum - 1) > 1e-3)
    top.fail_at(n, "mineral",
                fmt::format("the minerals' fractions sum to {:.6g} (must be 1)", sum));
  return minerals;
}

void read_grain_specimen(TomlSection& sec, TomlSection& top, ModelConfig& cfg) {
  GrainConfig g;
  auto& t = cfg.tessellation;
  if (sec.has("grain_file")) {
    std::filesystem::path p = sec.string("grain_file", nullptr);
    if (p.is_relative()) p = cfg.file.parent_path() / p;
    if (!file_exists(p))
      sec.fail("grain_file", fmt::format("grain file '{}' does not exist", p.string()));
    g.grain_file = p;
  } else {
    read_outline(sec, t.outline);
    g.settings.grain_size = specimen_length(sec, "grain_size");
  }
  const std::string voronoi = "voronoi";
  const std::string sub = sec.string("sub_blocks", &voronoi);
  if (sub == "trigon")
    g.settings.sub_blocks = geometry::SubBlocks::trigon;
  else if (sub != "voronoi")
    sec.fail("sub_blocks", fmt::format("must be \"voronoi\" or \"trigon\" (got \"{}\")", sub));
  g.settings.sub_block_size = specimen_length(sec, "sub_block_size");
  if (g.settings.grain_size > 0 && g.settings.sub_block_size > g.settings.grain_size)
    sec.fail("sub_block_size", "must not be larger than grain_size");
  g.settings.sub_block_lloyd_iterations =
      static_cast<int>(sec.integer("sub_block_lloyd_iterations", 3, 0, kMaxLloydIterations));
  t.lloyd_iterations = static_cast<int>(sec.integer("lloyd_iterations", 0, 0, kMaxLloydIterations));
  t.min_edge_length = sec.non_negative("min_edge_length", 0.0);
  sec.finish();
  g.minerals = read_minerals(top, !g.grain_file);
  std::vector<std::string> names;
  for (const Mineral& m : g.minerals) {
    g.settings.fractions.push_back(m.fraction);
    names.push_back(m.name);
    cfg.density += m.fraction * m.density;
  }
  if (g.grain_file) {
    g.settings.grains = read_grain_file(*g.grain_file, names);
    cfg.density = g.minerals.front().density;  // platens only: their mass never enters
  }
  cfg.grains = std::move(g);
}

void read_specimen(TomlSection sec, TomlSection& top, ModelConfig& cfg) {
  cfg.specimen_line = sec.line();
  const std::string voronoi = "voronoi";
  const std::string kind = sec.string("kind", &voronoi);
  if (kind == "grains") return read_grain_specimen(sec, top, cfg);
  if (kind != "voronoi")
    sec.fail("kind", fmt::format("must be \"voronoi\" or \"grains\" (got \"{}\")", kind));
  if (sec.has("file")) {
    std::filesystem::path p = sec.string("file", nullptr);
    if (p.is_relative()) p = cfg.file.parent_path() / p;
    if (!file_exists(p))
      sec.fail("file", fmt::format("specimen file '{}' does not exist", p.string()));
    cfg.specimen_file = p;
    sec.finish();  // a prepared specimen carries its own geometry: no other keys allowed
    return;
  }
  auto& t = cfg.tessellation;
  read_outline(sec, t.outline);
  if (sec.has("block_count") == sec.has("mean_edge_length"))
    sec.fail("block_count", "give exactly one of 'block_count' and 'mean_edge_length'");
  t.block_count = static_cast<int>(sec.integer("block_count", 0, 2, static_cast<long>(kMaxBlocks)));
  t.mean_edge_length = sec.has("mean_edge_length") ? specimen_length(sec, "mean_edge_length") : 0.0;
  t.lloyd_iterations = static_cast<int>(sec.integer("lloyd_iterations", 0, 0, kMaxLloydIterations));
  t.min_edge_length = sec.non_negative("min_edge_length", 0.0);
  sec.finish();
}

std::size_t mineral_index(TomlSection& sec, std::string_view key, std::string_view name,
                          const std::vector<Mineral>& minerals) {
  for (std::size_t m = 0; m < minerals.size(); ++m)
    if (minerals[m].name == name) return m;
  sec.fail(key, fmt::format("unknown mineral '{}'", name));
}

// A law that starts from `base` and replaces the keys `over` gives (read in place: a merged copy
// of the tables would lose every value's file and line).
LawChoice read_law_over(const toml::table& base, const toml::table& over, const std::string& path,
                        const std::string& file) {
  TomlSection sec(over, path, file, &base);
  LawChoice law = read_law(sec, "mohr_coulomb");
  sec.finish();
  return law;
}

// [joints.intergranular], [joints.transgranular], [joints.mineral.<name>] (transgranular inside
// grains of that mineral) and [joints.pair."<a>-<b>"] (intergranular between those minerals).
void read_grain_joints(TomlSection joints, GrainConfig& g) {
  for (auto [name, law] : {std::pair{"intergranular", &g.intergranular},
                           std::pair{"transgranular", &g.transgranular}}) {
    TomlSection sec = joints.sub(name);
    *law = read_law(sec, "mohr_coulomb");
    sec.finish();
  }
  const toml::table& inter = *joints.table().get(std::string_view("intergranular"))->as_table();
  const toml::table& trans = *joints.table().get(std::string_view("transgranular"))->as_table();
  g.inside.assign(g.minerals.size(), std::nullopt);
  if (joints.has("mineral")) {
    TomlSection list = joints.sub("mineral");
    for (const auto& [key, node] : list.table()) {
      const std::size_t m = mineral_index(list, key.str(), key.str(), g.minerals);
      if (!node.is_table()) list.fail(key.str(), "must be a table of contact law keys");
      g.inside[m] = read_law_over(trans, *node.as_table(), list.key_path(key.str()), joints.file());
      list.node(key.str());
    }
  }
  if (joints.has("pair")) {
    TomlSection list = joints.sub("pair");
    for (const auto& [key, node] : list.table()) {
      const std::string name(key.str());
      std::optional<std::pair<std::size_t, std::size_t>> found;
      for (std::size_t cut = name.find('-'); cut != std::string::npos;
           cut = name.find('-', cut + 1)) {
        std::size_t a = g.minerals.size(), b = a;
        for (std::size_t m = 0; m < g.minerals.size(); ++m) {
          if (g.minerals[m].name == name.substr(0, cut)) a = m;
          if (g.minerals[m].name == name.substr(cut + 1)) b = m;
        }
        if (a < g.minerals.size() && b < g.minerals.size()) found = {a, b};
      }
      if (!found)
        list.fail(name, "must name two minerals of [[mineral]] as \"<mineral>-<mineral>\"");
      if (!node.is_table()) list.fail(name, "must be a table of contact law keys");
      g.pairs.push_back(
          {found->first, found->second,
           read_law_over(inter, *node.as_table(), list.key_path(name), joints.file())});
      list.node(name);
    }
  }
  joints.finish();
}

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

// One [[stage]] table: a single stage, or a cyclic block expanded into its stages.
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

laws::NominalStiffness nominal_stiffness(const LawChoice& c) {
  return laws::find_law(c.name)->nominal_stiffness(c.params);
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

// [corrosion]: the constants of the two layers (docs/theory.md §14; [Liu2020] Table 4 for LdB
// granite).
void read_corrosion(TomlSection sec, TomlSection& top, ModelConfig& cfg) {
  if (!cfg.grains)
    top.fail("corrosion",
             "stress corrosion needs a grain-based specimen ([specimen] kind = "
             "\"grains\"): its layers act inside grains and on grain boundaries");
  CorrosionConfig c;
  c.rate.beta_up = sec.positive("beta_up", laws::required);
  c.rate.beta_low = sec.positive("beta_low", laws::required);
  c.rate.r_mid = sec.positive("r_mid", laws::required);
  c.rate.k_v = sec.number("k_v", laws::required);
  if (c.rate.k_v >= 0)
    sec.fail("k_v", fmt::format("must be negative: the rate rises with the driving-stress ratio "
                                "(got {})",
                                c.rate.k_v));
  c.beta3_per_beta1 = sec.positive("beta3_per_beta1", 1.0);
  c.transgranular = sec.boolean("transgranular", true);
  c.intergranular = sec.boolean("intergranular", true);
  if (!c.transgranular && !c.intergranular)
    sec.fail("intergranular", "at least one of transgranular and intergranular must be on");
  const GrainConfig& g = *cfg.grains;
  const auto bonded_law = [&](const LawChoice& law, const char* key) {
    if (!laws::find_law(law.name)->make(law.params, 0)->degradable_bonds())
      sec.fail(key, fmt::format("corrodes bonds that a law lets it degrade; law '{}' has none (its "
                                "strength is not a bond the corrosion layers can weaken)",
                                law.name));
  };
  // A layer switched off keeps its keys (a batch case may switch it), required only when on.
  const auto needed = [](bool on) { return on ? laws::required : 1.0; };
  if (c.transgranular) {
    bonded_law(g.transgranular, "transgranular");
    for (const auto& in : g.inside)
      if (in) bonded_law(*in, "transgranular");
  }
  c.bonded.beta2 = sec.positive("beta2", needed(c.transgranular));
  c.bonded.activation_stress = sec.non_negative("activation_stress", needed(c.transgranular));
  c.bonded.xi_a = sec.positive("min_length_ratio", 0.01);
  if (c.bonded.xi_a >= 1) sec.fail("min_length_ratio", "must be < 1");
  if (c.intergranular) {
    bonded_law(g.intergranular, "intergranular");
    for (const auto& p : g.pairs) bonded_law(p.law, "intergranular");
  }
  c.degradation.beta4 = sec.positive("beta4", needed(c.intergranular));
  c.degradation.m_s = sec.non_negative("activation_level", needed(c.intergranular) * 0.5);
  if (c.degradation.m_s >= 1) sec.fail("activation_level", "must be < 1");
  c.degradation.lambda_a = sec.positive("min_strength_factor", 0.01);
  if (c.degradation.lambda_a >= 1) sec.fail("min_strength_factor", "must be < 1");
  sec.finish();
  cfg.corrosion = c;
}

void read_stages(TomlSection sec, std::size_t index, std::vector<loading::Stage>& stages,
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
  st.ramp_time = sec.non_negative("ramp_time", 0.0);
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
  read_implicit_start(sec, st, index == 0 && stages.empty(), cfg);
  sec.finish();
  stages.push_back(st);
}

// Tables merge key by key; any other value (arrays such as [[stage]] included) replaces. The
// nodes of `over` are moved, not copied: a copied toml++ node loses its file and line.
void merge_into(toml::table& base, toml::table&& over) {
  for (auto&& [key, node] : over) {
    toml::node* old = base.get(key.str());
    if (old && old->is_table() && node.is_table())
      merge_into(*old->as_table(), std::move(*node.as_table()));
    else
      base.insert_or_assign(key, std::move(node));
  }
}

// A model file may start from another: `base = "file.toml"` (relative to it). Keys it sets win.
toml::table load(const std::filesystem::path& file, int depth,
                 std::vector<std::filesystem::path>& sources) {
  toml::table t = parse_toml_file(file);
  sources.push_back(file);
  const toml::node* b = t.get("base");
  if (!b) return t;
  const auto name = b->value_exact<std::string>();
  const auto line = b->source().begin.line;
  if (!name)
    throw ModelFileError(fmt::format("{}:{}: key 'base': must be a string", file.string(), line));
  const std::filesystem::path path = file.parent_path() / *name;
  if (depth >= 8 || !file_exists(path))
    throw ModelFileError(fmt::format(
        "{}:{}: key 'base': {}", file.string(), line,
        depth >= 8 ? "more than 8 nested base files" : "no such file: " + path.string()));
  toml::table merged = load(path, depth + 1, sources);
  t.erase("base");
  // A load path replaces the base's: [shpb] its [[stage]]s, [[stage]]s its [shpb].
  if (t.contains("shpb")) merged.erase("stage");
  if (t.contains("stage")) merged.erase("shpb");
  merge_into(merged, std::move(t));
  return merged;
}

// A length the specimen's blocks must exceed, and what it is, for messages.
struct Bound {
  double length;
  std::string what;
};

// The lengths of a specimen against one another, before it is tessellated: the block count
// (estimated from the outline area) stays bounded, the outline holds its blocks, and blocks are
// longer than the edges collapsed (min_edge_length) and the corners rounded (rounding_length).
void check_lengths(const toml::table& root, const ModelConfig& cfg) {
  if (cfg.specimen_file) return;  // a prepared specimen: its blocks are given
  const std::string file = cfg.file.string();
  TomlSection spec(*root.get("specimen")->as_table(), "specimen", file);
  const geometry::Outline& o = cfg.tessellation.outline;
  const bool disc = o.kind == geometry::OutlineKind::disc;
  double width = disc ? o.diameter : o.width, height = disc ? o.diameter : o.height;
  std::string narrow_key = disc ? "diameter" : o.width <= o.height ? "width" : "height";
  const GrainConfig* g = cfg.grains ? &*cfg.grains : nullptr;
  if (g && g->grain_file) {  // the outline is the grains' bounding box
    geometry::Point lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    geometry::Point hi{-lo.x, -lo.y};
    for (const geometry::Grain& grain : g->settings.grains)
      for (const geometry::Point p : grain.corners) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      }
    width = hi.x - lo.x;
    height = hi.y - lo.y;
    narrow_key = "grain_file";
    for (const double v : {width, height})
      if (!(v >= kMinLength && v <= kMaxLength))
        spec.fail("grain_file",
                  fmt::format("the grains span {:g} x {:g} m: each side must be between {:g} m "
                              "and {:g} m",
                              width, height, kMinLength, kMaxLength));
  }
  const double area = disc && !(g && g->grain_file) ? std::numbers::pi / 4 * o.diameter * o.diameter
                                                    : width * height;
  const double smallest = std::min(width, height);
  const auto circle = [](double diameter) { return std::numbers::pi / 4 * diameter * diameter; };

  // The block size: the side of the mean block's square, sqrt(area / blocks).
  double block = 0;
  std::string block_what;
  if (g) {
    const double s = g->settings.sub_block_size;
    if (!g->grain_file) {
      const double grain = g->settings.grain_size;
      const double grains = area / circle(grain);
      if (grains > kMaxBlocks)
        spec.fail("grain_size", fmt::format("gives about {:.3g} grains (outline area / (pi/4 "
                                            "grain_size^2)), more than the {:.0f} allowed",
                                            grains, kMaxBlocks));
      if (std::round(grains) < 2)
        spec.fail("grain_size", "is too large: fewer than 2 grains fit in the outline");
      if (!(kPoissonEdgeFactor * std::sqrt(circle(grain)) < smallest))
        spec.fail(narrow_key,
                  fmt::format("({}) must be larger than the grains' mean edge, about "
                              "0.65 sqrt(pi/4) grain_size = {}",
                              mm(smallest), mm(kPoissonEdgeFactor * std::sqrt(circle(grain)))));
    }
    const double subs = area / circle(s);
    if (subs > kMaxBlocks)
      spec.fail("sub_block_size", fmt::format("gives about {:.3g} sub-blocks (outline area / "
                                              "(pi/4 sub_block_size^2)), more than the {:.0f} "
                                              "allowed",
                                              subs, kMaxBlocks));
    block = std::sqrt(circle(s));
    block_what = fmt::format("the sub-block size sqrt(pi/4) sub_block_size = {}", mm(block));
  } else if (cfg.tessellation.block_count > 0) {
    const double n = cfg.tessellation.block_count;
    block = std::sqrt(area / n);
    block_what = fmt::format("the block size sqrt(area / block_count) = {}", mm(block));
    if (!(kPoissonEdgeFactor * block < smallest))
      spec.fail(narrow_key, fmt::format("({}) must be larger than the blocks' mean edge, about "
                                        "0.65 sqrt(area / block_count) = {}",
                                        mm(smallest), mm(kPoissonEdgeFactor * block)));
  } else {
    const double edge = cfg.tessellation.mean_edge_length;
    const double n = area * std::pow(kPoissonEdgeFactor / edge, 2);
    if (n > kMaxBlocks)
      spec.fail("mean_edge_length",
                fmt::format("gives about {:.3g} blocks (area x (0.65 / mean_edge_length)^2), more "
                            "than the {:.0f} allowed",
                            n, kMaxBlocks));
    if (!(edge < smallest))
      spec.fail("mean_edge_length",
                fmt::format("({}) must be smaller than the specimen ({})", mm(edge), mm(smallest)));
    if (std::round(n) < 2) spec.fail("mean_edge_length", "is too large: fewer than 2 blocks");
    block = edge / kPoissonEdgeFactor;
    block_what = fmt::format("the block size mean_edge_length / 0.65 = {}", mm(block));
  }

  // min_edge_length and 2 x rounding_length must be shorter than every length of the specimen.
  std::vector<Bound> lengths{
      {block, block_what},
      {smallest, fmt::format("the specimen's {} ({})", narrow_key, mm(smallest))}};
  if (g && !g->grain_file)
    lengths.push_back(
        {g->settings.grain_size, fmt::format("grain_size ({})", mm(g->settings.grain_size))});
  const Bound& shortest =
      *std::min_element(lengths.begin(), lengths.end(),
                        [](const Bound& a, const Bound& b) { return a.length < b.length; });
  const double min_edge = cfg.tessellation.min_edge_length;
  if (!(min_edge < shortest.length))
    spec.fail("min_edge_length",
              fmt::format("({}) must be shorter than {}", mm(min_edge), shortest.what));
  if (cfg.rounding_length > 0 || cfg.solver.contact_tolerance > 0) {
    TomlSection contact(*root.get("contact")->as_table(), "contact", file);
    if (!(2 * cfg.rounding_length < shortest.length))
      contact.fail("rounding_length", fmt::format("({}) must be shorter than half of {}",
                                                  mm(cfg.rounding_length), shortest.what));
    if (!(cfg.solver.contact_tolerance < block))
      contact.fail("tolerance", fmt::format("({}) must be shorter than {}",
                                            mm(cfg.solver.contact_tolerance), block_what));
  }
  if (cfg.deformable.enabled) {
    const double zones = 2 * area / std::pow(cfg.deformable.zone_size, 2);
    if (zones > kMaxZones)
      TomlSection(*root.get("blocks")->as_table(), "blocks", file)
          .fail("zone_size", fmt::format("gives about {:.3g} zones (2 x area / zone_size^2), more "
                                         "than the {:.0f} allowed",
                                         zones, kMaxZones));
  }
  if (cfg.output.damage_grid_cell > 0) {
    const double cells = area / std::pow(cfg.output.damage_grid_cell, 2);
    if (cells > kMaxDamageCells)
      TomlSection(*root.get("output")->as_table(), "output", file)
          .fail("damage_grid_cell",
                fmt::format("gives about {:.3g} cells (area / damage_grid_cell^2), more than the "
                            "{:.0f} allowed",
                            cells, kMaxDamageCells));
  }
}

// [shpb] with [shpb.incident_bar] and [shpb.transmitted_bar]; the transmitted bar takes the
// incident bar's diameter, E and density unless it gives its own.
ShpbConfig read_shpb(TomlSection sec) {
  ShpbConfig s;
  const auto bar = [&](TomlSection b, const loading::BarProperties* like,
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
        b.fail("gauges", fmt::format("a gauge at {} m is outside its bar (0, {} m) from the face",
                                     x, p.length));
    b.finish();
    return p;
  };
  s.incident = bar(sec.sub("incident_bar"), nullptr, s.incident_gauges);
  s.transmitted = bar(sec.sub("transmitted_bar"), &s.incident, s.transmitted_gauges);
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
  if (s.block_bars) {
    s.bar_block_length = sec.positive("bar_block_length", 0.1 * s.incident.width);
    if (!s.incident.quiet_far_end)
      sec.sub("incident_bar")
          .fail("far_end",
                "with bars = \"blocks\" the striker's pulse enters through the incident "
                "bar's far end, which absorbs what returns: far_end = \"quiet\"");
    if (s.transmitted.length < 2.0 * s.bar_block_length)
      sec.fail("bar_block_length",
               fmt::format("{} m: each bar needs at least two blocks", s.bar_block_length));
  } else if (sec.has("bar_block_length")) {
    sec.fail("bar_block_length", "only with bars = \"blocks\"");
  }
  s.duration = sec.positive("duration", 2.0 * pulse);
  s.record_interval = sec.positive("record_interval", pulse / 1000.0);
  s.equilibrium_tolerance = sec.positive("equilibrium_tolerance", 0.05);
  sec.finish();
  return s;
}

void read_root(const toml::table& root, ModelConfig& cfg) {
  const std::filesystem::path& file = cfg.file;
  TomlSection top(root, "", file.string());
  const std::string empty;
  cfg.title = top.string("title", &empty);
  cfg.seed = static_cast<std::uint64_t>(top.integer("seed", 1, 0));
  read_specimen(top.sub("specimen"), top, cfg);
  cfg.tessellation.seed = cfg.seed;

  if (cfg.grains) {
    if (top.has("blocks")) {  // only the zoning: density and elasticity are the minerals'
      TomlSection blocks = top.sub("blocks");
      for (const char* key : {"density", "E", "nu"})
        if (blocks.has(key))
          blocks.fail(key, "a grain-based specimen takes density, E and nu from each [[mineral]]");
      cfg.deformable.enabled = blocks.boolean("deformable", false);
      if (cfg.deformable.enabled) {
        cfg.deformable.zone_size = blocks.positive("zone_size", laws::required);
        for (const Mineral& m : cfg.grains->minerals)
          if (m.youngs_modulus == 0)
            blocks.fail("deformable", fmt::format("deformable grains need E and nu in every "
                                                  "[[mineral]]; '{}' has none",
                                                  m.name));
      }
      blocks.finish();
    }
    read_grain_joints(top.sub("joints"), *cfg.grains);
    cfg.joints = cfg.grains->intergranular;
  } else {
    TomlSection blocks = top.sub("blocks");
    cfg.density = blocks.positive("density", laws::required);
    cfg.deformable.enabled = blocks.boolean("deformable", false);
    if (cfg.deformable.enabled) {
      cfg.deformable.zone_size = blocks.positive("zone_size", laws::required);
      cfg.deformable.youngs_modulus = blocks.positive("E", laws::required);
      cfg.deformable.poisson_ratio = blocks.number("nu", laws::required);
      if (!(cfg.deformable.poisson_ratio > -1.0 && cfg.deformable.poisson_ratio < 0.5))
        blocks.fail("nu",
                    fmt::format("must be > -1 and < 0.5 (got {})", cfg.deformable.poisson_ratio));
    }
    blocks.finish();
    TomlSection joints = top.sub("joints");
    cfg.joints = read_law(joints, "mohr_coulomb");
    if (joints.has("mix")) {
      TomlSection mix = joints.sub("mix");
      ModelConfig::JointMix m;
      m.fraction = mix.positive("fraction", laws::required);
      if (m.fraction >= 1)
        mix.fail("fraction",
                 fmt::format("must be a fraction of the joints in (0, 1) (got {})", m.fraction));
      m.law = read_law(mix, "mohr_coulomb");
      mix.finish();
      cfg.joint_mix = std::move(m);
    }
    joints.finish();
  }

  // Platens: frictionless, no tension, as stiff as the joints' law's nominal springs unless given.
  const laws::NominalStiffness joint_springs = nominal_stiffness(cfg.joints);
  const double jkn_mean = joint_springs.normal;
  cfg.platens.name = "mohr_coulomb";
  if (top.has("platens")) {
    TomlSection p = top.sub("platens");
    cfg.platens.params["jkn"] = model::Distribution::constant(p.positive("jkn", jkn_mean));
    cfg.platens.params["friction"] = model::Distribution::constant(p.non_negative("friction", 0.0));
    if (cfg.platens.params["friction"].value >= 90) p.fail("friction", "must be < 90 deg");
    for (const char* k : {"jks", "tension", "cohesion", "dilation"})
      cfg.platens.params[k] = model::Distribution::constant(0.0);
    // Bonded platens glue to the specimen (direct tension): stronger than any joint by default.
    cfg.platens_bonded = p.boolean("bonded", false);
    if (cfg.platens_bonded) {
      const double jks_mean = joint_springs.shear;
      const auto strongest = [&](const char* k) {
        return cfg.joints.params.count(k) ? 100.0 * cfg.joints.params.at(k).mean() : 0.0;
      };
      cfg.platens.params["jks"] = model::Distribution::constant(p.positive("jks", jks_mean));
      cfg.platens.params["tension"] =
          model::Distribution::constant(p.positive("tension", strongest("tension")));
      cfg.platens.params["cohesion"] =
          model::Distribution::constant(p.positive("cohesion", strongest("cohesion")));
    }
    p.finish();
  } else {
    cfg.platens.params["jkn"] = model::Distribution::constant(jkn_mean);
    cfg.platens.params["friction"] = model::Distribution::constant(0.0);
    for (const char* k : {"jks", "tension", "cohesion", "dilation"})
      cfg.platens.params[k] = model::Distribution::constant(0.0);
  }

  static const toml::table no_table;
  TomlSection contact =
      top.has("contact") ? top.sub("contact") : TomlSection(no_table, "contact", file.string());
  cfg.rounding_length = contact.has("rounding_length") ? contact.positive("rounding_length", 0) : 0;
  cfg.solver.contact_tolerance = contact.has("tolerance") ? contact.positive("tolerance", 0) : 0;
  cfg.solver.overlap_limit = contact.positive("overlap_limit", 0.5);
  if (cfg.solver.overlap_limit >= 1)
    contact.fail("overlap_limit", "must be < 1: at 1 the rounded corner's centre reaches the edge");
  contact.finish();

  if (top.has("solver")) {
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
    if (const toml::node* g = s.node("gravity")) {
      const toml::array* a = g->as_array();
      if (!a || a->size() != 2 || !(*a)[0].is_number() || !(*a)[1].is_number())
        s.fail_at(g, "gravity", "must be an array of two numbers [gx, gy] in m/s^2");
      cfg.solver.gravity = {(*a)[0].value<double>().value(), (*a)[1].value<double>().value()};
      if (!std::isfinite(cfg.solver.gravity.x) || !std::isfinite(cfg.solver.gravity.y))
        s.fail_at(g, "gravity", "must hold finite numbers only");
    }
    s.finish();
  } else {
    cfg.max_steps = 20'000'000;
  }

  if (top.has("loading")) {
    TomlSection l = top.sub("loading");
    cfg.load_path.confining_stress = l.non_negative("confining_stress", 0.0);
    l.finish();
  }
  if (top.has("corrosion")) read_corrosion(top.sub("corrosion"), top, cfg);
  if (top.has("shpb")) {
    if (top.has("stage"))
      top.fail("stage", "a [shpb] test is its own load path: leave out the [[stage]] tables");
    if (cfg.load_path.confining_stress > 0)
      top.fail("loading", "a [shpb] test has no confinement: leave out confining_stress");
    if (cfg.solver.time_step > 0)
      TomlSection(*root["solver"].as_table(), "solver", file.string())
          .fail("time_step", "density scaling would change the inertia a [shpb] test measures");
    cfg.shpb = read_shpb(top.sub("shpb"));
  } else {
    const toml::node* stages = top.node("stage");
    if (!stages || !stages->is_array_of_tables())
      top.fail("stage", "at least one [[stage]] table (or a [shpb] test) is required");
    const toml::array& list = *stages->as_array();
    for (std::size_t i = 0; i < list.size(); ++i)
      read_stages(TomlSection(*list[i].as_table(), fmt::format("stage[{}]", i), file.string()), i,
                  cfg.load_path.stages, cfg);
  }

  if (top.has("quiet_boundary")) {
    TomlSection q = top.sub("quiet_boundary");
    QuietBoundaryConfig qb;
    const auto side_of = [&](const toml::node* where, std::string_view key,
                             const std::string& name) {
      const std::pair<const char*, loading::Side> names[] = {{"left", loading::Side::left},
                                                             {"right", loading::Side::right},
                                                             {"bottom", loading::Side::bottom},
                                                             {"top", loading::Side::top}};
      for (const auto& [n, s] : names)
        if (name == n) return s;
      q.fail_at(
          where, key,
          fmt::format("'{}' is not a side: \"left\", \"right\", \"bottom\" or \"top\"", name));
    };
    const toml::node* sides = q.node("sides");
    if (sides) {
      if (!sides->is_array()) q.fail("sides", "an array of sides, e.g. [\"left\", \"right\"]");
      for (const toml::node& e : *sides->as_array()) {
        if (!e.is_string()) q.fail_at(&e, "sides", "each side is a string, e.g. \"left\"");
        qb.sides.push_back(side_of(&e, "sides", *e.value<std::string>()));
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
    if (q.has("input_side")) {
      qb.input_side = side_of(q.node("input_side"), "input_side", q.string("input_side", nullptr));
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
    if (qb.sides.empty() && !qb.input_side)
      q.fail("sides", "name the absorbing sides (or an input_side)");
    if (cfg.deformable.enabled)
      q.fail("sides", "quiet boundaries need rigid blocks ([blocks] deformable = false)");
    if (cfg.shpb) q.fail("sides", "a [shpb] test's bars are its boundaries: no quiet boundary");
    q.finish();
    cfg.quiet_boundary = qb;
  }
  if (top.has("output")) {
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
  top.finish();
  check_lengths(root, cfg);
}

}  // namespace

ModelConfig read_model_file(const std::filesystem::path& file,
                            const std::vector<Override>& overrides) {
  ModelConfig cfg;
  cfg.file = file;
  toml::table root = load(file, 0, cfg.sources);
  for (const Override& o : overrides) apply_override(root, o, file.string());
  try {
    read_root(root, cfg);
  } catch (const ModelFileError& e) {
    for (auto o = overrides.rbegin(); o != overrides.rend(); ++o) {  // the last one set the value
      if (!concerns(e.key(), o->key)) continue;
      fail_override(
          *o, file.string(),
          e.key() == o->key ? e.reason() : fmt::format("key '{}': {}", e.key(), e.reason()));
    }
    throw;
  }
  if (cfg.specimen_file) cfg.sources.push_back(*cfg.specimen_file);
  if (cfg.grains && cfg.grains->grain_file) cfg.sources.push_back(*cfg.grains->grain_file);
  return cfg;
}

}  // namespace vorodec::io
