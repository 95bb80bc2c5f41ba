// [corrosion]: the constants of the stress-corrosion layers of a grain-based specimen.
#include <fmt/format.h>

#include "sections.hpp"

namespace vorodec::io {

namespace {

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

}  // namespace

void read_corrosion_table(TomlSection& top, ModelConfig& cfg) {
  if (top.has("corrosion")) read_corrosion(top.sub("corrosion"), top, cfg);
}

}  // namespace vorodec::io
