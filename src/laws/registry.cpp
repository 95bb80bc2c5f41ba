#include <array>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::laws {

// One row per law; each law's source defines its LawInfo.
extern const LawInfo mohr_coulomb_info;
extern const LawInfo linear_elastic_info;
extern const LawInfo burgers_info;
extern const LawInfo barton_bandis_info;

std::span<const LawInfo> law_registry() {
  static const std::array<LawInfo, 4> registry{mohr_coulomb_info, linear_elastic_info,
                                               burgers_info, barton_bandis_info};
  return registry;
}

const LawInfo* find_law(std::string_view name) {
  for (const LawInfo& info : law_registry())
    if (info.name == name) return &info;
  return nullptr;
}

}  // namespace vorodec::laws
