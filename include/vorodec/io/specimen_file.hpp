#pragma once
// A prepared specimen (`vorodec build`): the exact tessellation (hexadecimal floating point, so a
// reload is bit for bit) and, for reference, the initial contacts with their sampled properties.
#include <filesystem>
#include <string>

#include "vorodec/geometry/tessellation.hpp"

namespace vorodec::io {

void write_specimen(const std::filesystem::path& file, const geometry::Tessellation& tess,
                    const std::string& contacts_table);
// Throws ModelFileError naming the file and line of any malformed entry.
geometry::Tessellation read_specimen(const std::filesystem::path& file);

}  // namespace vorodec::io
