#include "vorodec/io/csv_writer.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "vorodec/io/atomic_file.hpp"

namespace vorodec::io {

namespace {

// Rows buffered before they are written without being asked (a long run's quiet phases).
constexpr std::size_t kBufferBytes = 1 << 16;

}  // namespace

std::string CsvWriter::format_header(std::span<const std::string> header) {
  std::string h;
  for (std::size_t i = 0; i < header.size(); ++i) h += (i ? "," : "") + header[i];
  return h + '\n';
}

std::string CsvWriter::format_row(std::span<const double> values, const std::string& last_text) {
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line += ',';
    fmt::format_to(std::back_inserter(line), "{:.10g}", values[i]);
  }
  if (!last_text.empty()) line += "," + last_text;
  return line + '\n';
}

// The header goes in whole with the file (a kill leaves the old file or one with its header).
CsvWriter::CsvWriter(const std::filesystem::path& file, std::span<const std::string> header)
    : file_(file) {
  const std::string h = format_header(header);
  write_file_atomically(file, h);
  fd_ = open_for_writing(file, O_WRONLY | O_APPEND);
  written_ = h.size();
}

CsvWriter::CsvWriter(const std::filesystem::path& file, std::uint64_t bytes) : file_(file) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec || size < bytes)
    throw std::runtime_error(fmt::format("'{}' is {} than it was at the checkpoint", file.string(),
                                         ec ? "missing" : "shorter"));
  fd_ = open_for_writing(file, O_WRONLY);
  if (::ftruncate(fd_, static_cast<off_t>(bytes)) != 0 ||
      ::lseek(fd_, static_cast<off_t>(bytes), SEEK_SET) < 0) {
    ::close(fd_);
    throw std::runtime_error(fmt::format("cannot cut '{}' back to its checkpoint: {}",
                                         file.string(), std::strerror(errno)));
  }
  written_ = bytes;
}

CsvWriter::~CsvWriter() {
  try {
    flush();
  } catch (const std::exception&) {  // a destructor cannot report it; the next write did
  }
  ::close(fd_);
}

void CsvWriter::row(std::span<const double> values, const std::string& last_text) {
  buffer_ += format_row(values, last_text);
  if (buffer_.size() >= kBufferBytes) flush();
}

void CsvWriter::flush() {
  if (buffer_.empty()) return;
  write_all(fd_, buffer_, file_);
  written_ += buffer_.size();
  buffer_.clear();
}

}  // namespace vorodec::io
