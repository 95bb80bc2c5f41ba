#pragma once
// Overrides change the parsed model-file table before it is read, so they pass the same checks.
#include <toml++/toml.h>

#include <string>
#include <vector>

#include "vorodec/input/model_file.hpp"

namespace vorodec::io {

class TomlSection;

// A value as TOML text; floats in their shortest exact form (5e6 -> 5000000.0, 0.005 -> 0.005).
std::string toml_text(const toml::node& n);

// The section's `set` table of overrides ("a.b" = v and a.b = v alike), if any.
std::vector<Override> read_set(TomlSection& sec);

// Sets `o.key` in `root`, creating missing tables; throws ModelFileError naming `o.origin` when the
// path cannot be followed (a value where a table is needed, an index past an array's end).
void apply_override(toml::table& root, const Override& o, const std::string& file);

// Whether an error about `error_key` concerns the override of `override_key` (same key, a key
// inside it, or a table it created).
bool concerns(const std::string& error_key, const std::string& override_key);

[[noreturn]] void fail_override(const Override& o, const std::string& file,
                                const std::string& message);

}  // namespace vorodec::io
