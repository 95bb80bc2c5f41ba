#include "vorodec/laws/reference.hpp"

#include <fmt/format.h>

#include <cmath>

namespace vorodec::laws {

std::string range_text(const ParamSpec& spec) {
  return spec.max < 1e299
             ? fmt::format("{} {} and <= {} {}", spec.min_inclusive ? ">=" : ">", spec.min,
                           spec.max, spec.unit)
             : fmt::format("{} {} {}", spec.min_inclusive ? ">=" : ">", spec.min, spec.unit);
}

namespace {

std::string default_text(const ParamSpec& p) {
  if (!std::isnan(p.default_value)) return fmt::format("{}", p.default_value);
  return p.optional ? "see meaning" : "required";
}

}  // namespace

std::string law_reference() {
  std::string out;
  for (const LawInfo& law : law_registry()) {
    out += fmt::format("### `law = \"{}\"`\n\n{}.\n\n", law.name, law.doc);
    out += "| Key | Unit | Default | Valid | Weibull | Meaning |\n|---|---|---|---|---|---|\n";
    for (const ParamSpec& p : law.params)
      out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", p.key, p.unit, default_text(p),
                         range_text(p), p.distributable ? "yes" : "no", p.doc);
    out += "\n";
  }
  return out;
}

}  // namespace vorodec::laws
