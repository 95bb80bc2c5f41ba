#pragma once
// Cracks of grain-based specimens: intergranular (between two grains, or against a bonded
// platen) or transgranular (inside one grain), each tensile or shear.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::measure {

inline constexpr std::size_t kCrackClasses = 4;
// Class k (0..3) is written as k + 1 in VTK output.
inline constexpr std::array<std::string_view, kCrackClasses> kCrackClassNames = {
    "intergranular_tensile", "intergranular_shear", "transgranular_tensile", "transgranular_shear"};

// 0..3 in the order of kCrackClassNames; grain_of_block covers the specimen blocks.
std::size_t crack_class(const laws::CrackEvent& e, std::span<const std::int32_t> grain_of_block);

struct GrainCracks {
  std::array<std::size_t, kCrackClasses> count{};
  std::array<double, kCrackClasses> length{};  // m, summed crack (contact) lengths
};

GrainCracks grain_cracks(std::span<const laws::CrackEvent> cracks,
                         std::span<const std::int32_t> grain_of_block);

}  // namespace vorodec::measure
