#pragma once
// A CSV file written in whole rows: rows collect in a buffer that goes to the file only whole
// (flush), so a killed run leaves no partial row. A run that resumes reopens the file at the size
// it had at its checkpoint.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace vorodec::io {

class CsvWriter {
 public:
  // A new file with this header.
  CsvWriter(const std::filesystem::path& file, std::span<const std::string> header);
  // An existing file cut back to `bytes` (a size() it had), to be continued.
  CsvWriter(const std::filesystem::path& file, std::uint64_t bytes);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  void row(std::span<const double> values, const std::string& last_text = {});
  // Writes the buffered rows.
  void flush();
  // Bytes of the file once flushed.
  std::uint64_t size() const { return written_ + buffer_.size(); }
  // One row as the file holds it, newline included.
  static std::string format_row(std::span<const double> values, const std::string& last_text);
  static std::string format_header(std::span<const std::string> header);

 private:
  std::filesystem::path file_;
  int fd_ = -1;
  std::string buffer_;
  std::uint64_t written_ = 0;
};

}  // namespace vorodec::io
