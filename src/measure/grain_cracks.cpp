#include "vorodec/measure/grain_cracks.hpp"

namespace vorodec::measure {

std::size_t crack_class(const laws::CrackEvent& e, std::span<const std::int32_t> grain_of_block) {
  const auto a = static_cast<std::size_t>(e.a), b = static_cast<std::size_t>(e.b);
  const bool inside = a < grain_of_block.size() && b < grain_of_block.size() &&
                      grain_of_block[a] == grain_of_block[b];
  const bool shear = e.type != laws::ContactEvent::tensile_failure;
  return (inside ? 2u : 0u) + (shear ? 1u : 0u);
}

GrainCracks grain_cracks(std::span<const laws::CrackEvent> cracks,
                         std::span<const std::int32_t> grain_of_block) {
  GrainCracks g;
  for (const laws::CrackEvent& e : cracks) {
    const std::size_t k = crack_class(e, grain_of_block);
    ++g.count[k];
    g.length[k] += e.length;
  }
  return g;
}

}  // namespace vorodec::measure
