// The contact laws: the law a table chooses and its properties, [joints] (with [joints.mix], or a
// grain-based specimen's laws by mineral and mineral pair), [platens] and [contact].
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <utility>

#include "sections.hpp"
#include "vorodec/laws/reference.hpp"

namespace vorodec::io {

namespace {

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

std::size_t mineral_index(TomlSection& sec, std::string_view key, std::string_view name,
                          const std::vector<Mineral>& minerals) {
  for (std::size_t m = 0; m < minerals.size(); ++m)
    if (minerals[m].name == name) return m;
  sec.fail(key, fmt::format("unknown mineral '{}'", name));
}

// The minerals of "<mineral>-<mineral>" (names may hold '-': every cut is tried, the last wins).
std::optional<std::pair<std::size_t, std::size_t>> mineral_pair(
    const std::string& name, const std::vector<Mineral>& minerals) {
  std::optional<std::pair<std::size_t, std::size_t>> found;
  for (std::size_t cut = name.find('-'); cut != std::string::npos; cut = name.find('-', cut + 1)) {
    std::size_t a = minerals.size(), b = a;
    for (std::size_t m = 0; m < minerals.size(); ++m) {
      if (minerals[m].name == name.substr(0, cut)) a = m;
      if (minerals[m].name == name.substr(cut + 1)) b = m;
    }
    if (a < minerals.size() && b < minerals.size()) found = {a, b};
  }
  return found;
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
      const auto found = mineral_pair(name, g.minerals);
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

// [joints] of a Voronoi specimen: one law, and [joints.mix] a second for a fraction of them.
void read_voronoi_joints(TomlSection joints, ModelConfig& cfg) {
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

// No shear spring, tension, cohesion or dilation (bonded platens then give their own).
void zero_unbonded_params(LawChoice& platens) {
  for (const char* k : {"jks", "tension", "cohesion", "dilation"})
    platens.params[k] = model::Distribution::constant(0.0);
}

void read_platens(TomlSection p, const laws::NominalStiffness& joint_springs, ModelConfig& cfg) {
  const double jkn_mean = joint_springs.normal;
  cfg.platens.params["jkn"] = model::Distribution::constant(p.positive("jkn", jkn_mean));
  cfg.platens.params["friction"] = model::Distribution::constant(p.non_negative("friction", 0.0));
  if (cfg.platens.params["friction"].value >= 90) p.fail("friction", "must be < 90 deg");
  zero_unbonded_params(cfg.platens);
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
}

}  // namespace

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

laws::NominalStiffness nominal_stiffness(const LawChoice& c) {
  return laws::find_law(c.name)->nominal_stiffness(c.params);
}

void read_joints_table(TomlSection& top, ModelConfig& cfg) {
  if (!cfg.grains) return read_voronoi_joints(top.sub("joints"), cfg);
  read_grain_joints(top.sub("joints"), *cfg.grains);
  cfg.joints = cfg.grains->intergranular;
}

// Platens: frictionless, no tension, as stiff as the joints' law's nominal springs unless given.
void read_platens_table(TomlSection& top, ModelConfig& cfg) {
  const laws::NominalStiffness joint_springs = nominal_stiffness(cfg.joints);
  cfg.platens.name = "mohr_coulomb";
  if (top.has("platens")) return read_platens(top.sub("platens"), joint_springs, cfg);
  cfg.platens.params["jkn"] = model::Distribution::constant(joint_springs.normal);
  cfg.platens.params["friction"] = model::Distribution::constant(0.0);
  zero_unbonded_params(cfg.platens);
}

void read_contact_table(TomlSection& top, ModelConfig& cfg) {
  static const toml::table no_table;
  TomlSection contact =
      top.has("contact") ? top.sub("contact") : TomlSection(no_table, "contact", top.file());
  cfg.rounding_length = contact.has("rounding_length") ? contact.positive("rounding_length", 0) : 0;
  cfg.solver.contact_tolerance = contact.has("tolerance") ? contact.positive("tolerance", 0) : 0;
  cfg.solver.overlap_limit = contact.positive("overlap_limit", 0.5);
  if (cfg.solver.overlap_limit >= 1)
    contact.fail("overlap_limit", "must be < 1: at 1 the rounded corner's centre reaches the edge");
  contact.finish();
}

}  // namespace vorodec::io
