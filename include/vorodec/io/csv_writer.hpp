#pragma once
// A CSV file written row by row and flushed as it goes, so a long run can be watched.
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace vorodec::io {

class CsvWriter {
 public:
  CsvWriter(const std::filesystem::path& file, std::span<const std::string> header);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  void row(std::span<const double> values, const std::string& last_text = {});
  void flush();

 private:
  std::FILE* f_ = nullptr;
  std::string line_;
};

}  // namespace vorodec::io
