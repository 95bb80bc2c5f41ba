// [in_situ]: the initial stress field (loading/in_situ.hpp, docs/loading.md "In-situ stress").
#include <fmt/format.h>

#include "sections.hpp"

namespace vorodec::io {

namespace {

loading::StressTensor read_tensor(TomlSection& s, std::string_view key, bool required) {
  if (!required && !s.has(key)) return {0, 0, 0};
  const std::vector<double> v = s.numbers(key);
  if (v.size() != 3) s.fail(key, "must be an array of three numbers [xx, yy, xy]");
  return {v[0], v[1], v[2]};
}

// A law whose state a force alone does not give (Burger's: its dashpots' history).
void check_law(TomlSection& s, const LawChoice& law) {
  if (law.name == "burgers")
    s.fail("stress", fmt::format("the law '{}' cannot start loaded: its creep elements have a "
                                 "history a force does not give; bring the stress on by stages",
                                 law.name));
}

loading::InSituStress read_in_situ(TomlSection s, const ModelConfig& cfg) {
  loading::InSituStress f;
  f.stress = read_tensor(s, "stress", true);
  f.gradient = read_tensor(s, "gradient", false);
  if (s.has("datum_y")) f.datum_y = s.number("datum_y", laws::required);
  if (cfg.load_path.confining_stress != 0.0)
    s.fail("stress", "the in-situ stress holds the sides itself: remove loading.confining_stress");
  if ((f.stress.xy != 0.0 || f.gradient.xy != 0.0) && !cfg.platens_bonded)
    s.fail("stress",
           "a shear stress xy needs platens that hold it: [platens] bonded = true "
           "(unbonded platens have no shear spring)");
  if (cfg.tables.contains("shpb")) s.fail("stress", "a pressure-bar test starts unloaded");
  for (const LawChoice* law : {&cfg.joints, &cfg.platens}) check_law(s, *law);
  if (cfg.joint_mix) check_law(s, cfg.joint_mix->law);
  for (const auto& set : cfg.joint_sets) check_law(s, set.law);
  if (cfg.grains) {
    for (const LawChoice* law : {&cfg.grains->intergranular, &cfg.grains->transgranular})
      check_law(s, *law);
    for (const auto& inside : cfg.grains->inside)
      if (inside) check_law(s, *inside);
    for (const auto& p : cfg.grains->pairs) check_law(s, p.law);
  }
  s.finish();
  return f;
}

}  // namespace

void read_in_situ_table(TomlSection& top, ModelConfig& cfg) {
  if (top.has("in_situ")) cfg.in_situ = read_in_situ(top.sub("in_situ"), cfg);
}

}  // namespace vorodec::io
