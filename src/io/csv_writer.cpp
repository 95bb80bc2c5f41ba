#include "vorodec/io/csv_writer.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace vorodec::io {

CsvWriter::CsvWriter(const std::filesystem::path& file, std::span<const std::string> header) {
  f_ = std::fopen(file.string().c_str(), "w");
  if (!f_) throw std::runtime_error(fmt::format("cannot write '{}'", file.string()));
  std::string h;
  for (std::size_t i = 0; i < header.size(); ++i) h += (i ? "," : "") + header[i];
  std::fprintf(f_, "%s\n", h.c_str());
}

CsvWriter::~CsvWriter() {
  if (f_) std::fclose(f_);
}

void CsvWriter::row(std::span<const double> values, const std::string& last_text) {
  line_.clear();
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line_ += ',';
    fmt::format_to(std::back_inserter(line_), "{:.10g}", values[i]);
  }
  if (!last_text.empty()) line_ += "," + last_text;
  std::fprintf(f_, "%s\n", line_.c_str());
}

void CsvWriter::flush() {
  std::fflush(f_);
}

}  // namespace vorodec::io
