#pragma once
// Grain polygons with mineral labels (e.g. traced from a thin section), one row per corner:
//   grain_id,mineral,x,y
// x, y in m; the corners of one grain are consecutive rows in order along its boundary (either
// orientation); a header row and '#' comment lines are allowed. Bad input throws ModelFileError
// naming file:line.
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "vorodec/geometry/grains.hpp"

namespace vorodec::io {

// Minerals are looked up by name in `minerals` (their index becomes Grain::mineral).
std::vector<geometry::Grain> read_grain_file(const std::filesystem::path& file,
                                             std::span<const std::string> minerals);

}  // namespace vorodec::io
