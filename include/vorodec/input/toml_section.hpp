#pragma once
// Reads one TOML table key by key, remembering which keys were used, so that anything left over
// (a misspelled key) is reported with its line. Every error names file, key and line.
#include <toml++/toml.h>

#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "vorodec/input/model_file.hpp"

namespace vorodec::io {

// A TOML file parsed; a syntax error or an unreadable file throws ModelFileError with file:line.
toml::table parse_toml_file(const std::filesystem::path& file);

class TomlSection {
 public:
  // Keys absent from `table` are looked up in `inherited` (if given), read in place so that its
  // values keep their file and line; finish() reports unknown keys of either.
  TomlSection(const toml::table& table, std::string path, std::string file,
              const toml::table* inherited = nullptr);

  bool has(std::string_view key) const { return find(key) != nullptr; }
  double number(std::string_view key, double fallback);  // fallback NaN: required
  double positive(std::string_view key, double fallback);
  double non_negative(std::string_view key, double fallback);
  // An integer in [min, max]; keys stored in an int pass max <= INT_MAX.
  long integer(std::string_view key, long fallback, long min,
               long max = std::numeric_limits<long>::max());
  std::string string(std::string_view key, const std::string* fallback);
  bool boolean(std::string_view key, bool fallback);
  std::vector<double> numbers(std::string_view key);  // a required non-empty array of numbers
  const toml::node* node(std::string_view key);       // marks used; nullptr if absent
  TomlSection sub(std::string_view key);              // a required sub-table

  // Throws for any key that was never asked for (with a "did you mean" hint).
  void finish() const;

  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  [[noreturn]] void fail_at(const toml::node* where, std::string_view key,
                            const std::string& message) const;
  std::string key_path(std::string_view key) const;
  const toml::node* find(std::string_view key) const;  // does not mark the key used
  const toml::table& table() const { return table_; }
  const std::string& file() const { return file_; }
  int line() const { return static_cast<int>(table_.source().begin.line); }

 private:
  const toml::table& table_;
  const toml::table* inherited_;
  std::string path_, file_;
  std::set<std::string, std::less<>> used_;
};

}  // namespace vorodec::io
