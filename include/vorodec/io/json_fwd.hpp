#pragma once
// The JSON value type by name only, for headers that pass it on (io/json.hpp has the library).
#include <nlohmann/json_fwd.hpp>

namespace vorodec::io {

using Json = nlohmann::ordered_json;

}  // namespace vorodec::io
