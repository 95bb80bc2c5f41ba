#pragma once
// JSON files (summary.json and the others the project writes or reads), through nlohmann-json:
// keys in the order they are set, text escaped by the library, UTF-8 kept as it is.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "vorodec/io/json_fwd.hpp"

namespace vorodec::io {

// x rounded to `digits` significant digits, or null when it is not finite (JSON has no NaN or
// infinity). The file then holds the shortest text of that rounded double, so a reader gets the
// same number whether it reads the text or the value.
Json rounded(double x, int digits);
// x rounded to `decimals` decimal places (wall times), or null.
Json fixed(double x, int decimals);

// Written whole (io/atomic_file.hpp), indented by two spaces, ending in a newline.
void write_json_atomically(const std::filesystem::path& file, const Json& value);

// The file parsed; an unreadable or malformed file throws std::runtime_error naming it.
Json read_json_file(const std::filesystem::path& file);

}  // namespace vorodec::io
