// summary.json is written by a JSON library: any model file name and title read back exactly.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "run_support.hpp"
#include "vorodec/io/json.hpp"

namespace fs = std::filesystem;
using namespace vorodec::testing;

TEST(SummaryJson, NameAndTitleWithQuotesBackslashesAndNonAsciiReadBackExactly) {
  const fs::path dir = out_dir("summary_json");
  fs::create_directories(dir);
  const std::string name = "my \"test\" \\ Carrara-\xC3\xBC.toml";  // ü in UTF-8
  const std::string title =
      "Marble \"Carrara\" \\ \xE5\xA4\xA7\xE7\x90\x86\xE7\x9F\xB3 \xE2\x80\x94 ok";
  const std::string model = slurp(fs::path(VORODEC_SOURCE_DIR) / "tests/models/e2e_small.toml");
  // The title as a TOML basic string (quotes and backslashes escaped) in place of e2e's.
  std::string toml_title;
  for (const char c : title) {
    if (c == '"' || c == '\\') toml_title += '\\';
    toml_title += c;
  }
  const auto begin = model.find("title = \"") + 9, end = model.find('"', begin);
  std::ofstream(dir / name) << model.substr(0, begin) + toml_title + model.substr(end);
  const fs::path out = dir / "out";
  ASSERT_EQ(run_vorodec("run '" + (dir / name).string() + "' --max-steps 20 --no-vtk --threads 1 " +
                        "--out " + out.string()),
            0);
  const vorodec::io::Json summary = vorodec::io::read_json_file(out / "summary.json");
  EXPECT_EQ(summary.at("model").get<std::string>(), name);
  EXPECT_EQ(summary.at("title").get<std::string>(), title);
  EXPECT_EQ(summary.at("steps").get<long>(), 20);
}
