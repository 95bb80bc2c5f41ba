#pragma once
// The keys a batch file and a calibration file share.
#include <filesystem>
#include <string>

#include "vorodec/input/toml_section.hpp"

namespace vorodec::workflows {

// title, and output: the results folder (results/<the file's stem> unless given).
inline void read_title_and_output(io::TomlSection& top, const std::filesystem::path& file,
                                  std::string& title, std::filesystem::path& output) {
  const std::string empty;
  title = top.string("title", &empty);
  const std::string default_out = (std::filesystem::path("results") / file.stem()).string();
  output = top.string("output", &default_out);
  if (output.empty()) top.fail("output", "must name a folder");
}

}  // namespace vorodec::workflows
