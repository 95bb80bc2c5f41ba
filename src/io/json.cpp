#include "vorodec/io/json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "vorodec/io/atomic_file.hpp"

namespace vorodec::io {

Json rounded(double x, int digits) {
  if (!std::isfinite(x)) return nullptr;
  return std::stod(fmt::format("{:.{}g}", x, digits));
}

Json fixed(double x, int decimals) {
  if (!std::isfinite(x)) return nullptr;
  return std::stod(fmt::format("{:.{}f}", x, decimals));
}

void write_json_atomically(const std::filesystem::path& file, const Json& value) {
  // Invalid UTF-8 (a file name in another encoding) becomes U+FFFD instead of an exception.
  write_file_atomically(file, value.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

Json read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open", file.string()));
  try {
    return Json::parse(in);
  } catch (const Json::exception& e) {
    throw std::runtime_error(fmt::format("{}: not valid JSON: {}", file.string(), e.what()));
  }
}

}  // namespace vorodec::io
