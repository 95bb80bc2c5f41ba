// docs/model-file.md documents every key the readers ask for, and its contact-law tables are the
// laws' own parameter specs (`vorodec laws`), so neither can drift from the code.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "run_support.hpp"

namespace fs = std::filesystem;
using namespace vorodec::testing;

namespace {

const fs::path source = VORODEC_SOURCE_DIR;

bool identifier_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

// The identifiers of `text`, added to `words`.
void add_identifiers(const std::string& text, std::set<std::string>& words) {
  std::string word;
  for (const char c : text + ' ') {
    if (identifier_char(c)) {
      word += c;
    } else if (!word.empty()) {
      words.insert(word);
      word.clear();
    }
  }
}

// Every identifier inside the page's `code spans` and [table] headings. (A scan by hand: GCC 12
// warns falsely inside std::regex under the sanitizers.)
std::set<std::string> documented(const fs::path& page) {
  const std::string text = slurp(page);
  std::set<std::string> words;
  for (std::size_t at = 0; (at = text.find_first_of("`[", at)) != std::string::npos; ++at) {
    const char close = text[at] == '`' ? '`' : ']';
    const auto end = text.find(close, at + 1);
    if (end == std::string::npos) break;
    const std::string inside = text.substr(at + 1, end - at - 1);
    if (inside.find('\n') != std::string::npos) continue;  // not a span: the next line's
    if (close == '`') {
      at = end;
    } else if (inside.find_first_not_of("abcdefghijklmnopqrstuvwxyz_.[") != std::string::npos) {
      continue;  // a link or a citation, not a table heading
    }
    add_identifiers(inside, words);
  }
  return words;
}

// The keys a reader's source files ask a TomlSection for by name (`method("key"`), each with a
// file asking for it.
std::map<std::string, fs::path> asked_for(const std::vector<fs::path>& reader) {
  std::map<std::string, fs::path> keys;
  for (const fs::path& file : reader) {
    const std::string text = slurp(file);
    for (const std::string method :
         {"number", "positive", "non_negative", "integer", "string", "boolean", "numbers", "node",
          "sub", "has", "specimen_length"}) {
      const std::string call = method + "(\"";
      for (auto at = text.find(call); at != std::string::npos; at = text.find(call, at + 1)) {
        if (at > 0 && identifier_char(text[at - 1])) continue;  // part of a longer name
        const auto begin = at + call.size(), end = text.find('"', begin);
        const std::string key = text.substr(begin, end - begin);
        if (!key.empty() && std::all_of(key.begin(), key.end(), identifier_char))
          keys.emplace(key, file);
      }
    }
  }
  return keys;
}

// The model-file reader: every src/input/*.cpp but override.cpp, whose one key (`set`) is the
// batch and calibration files' (docs/workflows.md), and the stage modes' and drivers' own readers
// (src/drivers/).
std::vector<fs::path> model_file_reader() {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(source / "src/input"))
    if (e.path().extension() == ".cpp" && e.path().filename() != "override.cpp")
      files.push_back(e.path());
  for (const fs::directory_entry& e : fs::directory_iterator(source / "src/drivers"))
    if (e.path().extension() == ".cpp") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Whether `page` documents every key `reader` asks for (and the scan still finds its keys).
::testing::AssertionResult documents(const fs::path& page, const std::vector<fs::path>& reader) {
  const std::map<std::string, fs::path> keys = asked_for(reader);
  if (keys.size() <= 5)
    return ::testing::AssertionFailure()
           << "the scan found only " << keys.size() << " keys in " << reader.front();
  const std::set<std::string> words = documented(page);
  ::testing::AssertionResult result = ::testing::AssertionSuccess();
  for (const auto& [key, file] : keys)
    if (!words.count(key))
      result = ::testing::AssertionFailure()
               << "`" << key << "` of " << file << " is not in " << page;
  return result;
}

}  // namespace

TEST(ModelFileReference, EveryKeyTheReadersAskForIsDocumented) {
  EXPECT_TRUE(documents(source / "docs/model-file.md", model_file_reader()));
  EXPECT_TRUE(documents(source / "docs/workflows.md", {source / "src/workflows/batch_file.cpp",
                                                       source / "src/workflows/plan_keys.hpp",
                                                       source / "src/input/override.cpp"}));
  EXPECT_TRUE(documents(
      source / "docs/workflows.md",
      {source / "src/workflows/calibration_file.cpp", source / "src/workflows/plan_keys.hpp"}));
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
