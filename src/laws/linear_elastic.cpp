#include "vorodec/laws/linear_elastic.hpp"

#include "vorodec/laws/law_group.hpp"

namespace vorodec::laws {

namespace {
constexpr ParamSpec linear_elastic_params[] = {
    {"jkn", "Pa/m", "joint normal stiffness per unit contact length", 0, false, 1e300, required,
     true, false},
    {"jks", "Pa/m", "joint shear stiffness per unit contact length", 0, true, 1e300, required, true,
     false},
};
}  // namespace

extern const LawInfo linear_elastic_info;
const LawInfo linear_elastic_info{
    LinearElastic::name, "Linear normal and shear springs without strength (never fail)",
    linear_elastic_params,
    [](const LawParams& p, std::uint64_t seed) -> std::unique_ptr<LawGroup> {
      return std::make_unique<LawGroupOf<LinearElastic>>(p, seed);
    },
    [](const LawParams& p) {
      return NominalStiffness{mean_of(p, "jkn"), mean_of(p, "jks")};
    }};

}  // namespace vorodec::laws
