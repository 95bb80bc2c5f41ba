// docs/model-file.md documents every key the readers ask for, and its contact-law tables are the
// laws' own parameter specs (`vorodec laws`), so neither can drift from the code.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "run_support.hpp"

namespace fs = std::filesystem;
using namespace vorodec::testing;

namespace {

const fs::path source = VORODEC_SOURCE_DIR;

// Every identifier inside the page's `code spans` and [table] headings.
std::set<std::string> documented(const fs::path& page) {
  const std::string text = slurp(page);
  std::set<std::string> words;
  const std::regex span(R"re(`([^`\n]*)`|\[([a-z_.\[\]]+)\])re"), word("[a-z_0-9]+");
  for (std::sregex_iterator s(text.begin(), text.end(), span), end; s != end; ++s) {
    const std::string inside = (*s)[1].matched ? (*s)[1].str() : (*s)[2].str();
    for (std::sregex_iterator w(inside.begin(), inside.end(), word); w != end; ++w)
      words.insert(w->str());
  }
  return words;
}

// The keys a reader's source files ask a TomlSection for by name, each with a file asking for it.
std::map<std::string, fs::path> asked_for(const std::vector<fs::path>& reader) {
  const std::regex call(
      R"re(\b(?:number|positive|non_negative|integer|string|boolean|numbers|node|sub|has|)re"
      R"re(specimen_length)\("([a-z_0-9]+)")re");
  std::map<std::string, fs::path> keys;
  for (const fs::path& file : reader) {
    const std::string text = slurp(file);
    for (std::sregex_iterator m(text.begin(), text.end(), call), end; m != end; ++m)
      keys.emplace((*m)[1].str(), file);
  }
  return keys;
}

// The model-file reader: every src/input/*.cpp but override.cpp, whose one key (`set`) is the
// batch and calibration files' (docs/workflows.md).
std::vector<fs::path> model_file_reader() {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(source / "src/input"))
    if (e.path().extension() == ".cpp" && e.path().filename() != "override.cpp")
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

void expect_documented(const std::vector<fs::path>& reader, const fs::path& page) {
  const std::map<std::string, fs::path> keys = asked_for(reader);
  const std::set<std::string> words = documented(page);
  EXPECT_GT(keys.size(), 5u) << reader.front();  // the pattern still finds the reader's keys
  for (const auto& [key, file] : keys)
    EXPECT_TRUE(words.count(key)) << "`" << key << "` of " << file << " is not in " << page;
}

}  // namespace

TEST(ModelFileReference, EveryKeyTheReadersAskForIsDocumented) {
  expect_documented(model_file_reader(), source / "docs/model-file.md");
  expect_documented({source / "src/workflows/batch_file.cpp", source / "src/input/override.cpp"},
                    source / "docs/workflows.md");
  expect_documented({source / "src/workflows/calibration_file.cpp"}, source / "docs/workflows.md");
}

TEST(ModelFileReference, LawTablesAreTheLawsOwnParameterSpecs) {
  const Outcome o = run_capture("laws");
  ASSERT_EQ(o.code, 0) << o.output;
  const std::string page = slurp(source / "docs/model-file.md");
  const std::string begin = "<!-- vorodec laws: begin -->\n", end = "<!-- vorodec laws: end -->";
  const auto from = page.find(begin), to = page.find(end);
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  EXPECT_EQ(page.substr(from + begin.size(), to - from - begin.size()), o.output)
      << "regenerate with scripts/update-law-reference.sh";
}
