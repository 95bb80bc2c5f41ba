#include "vorodec/io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace vorodec::io {

int open_for_writing(const std::filesystem::path& file, int flags) {
  const int fd = ::open(file.string().c_str(), flags | O_CLOEXEC, 0644);
  if (fd < 0)
    throw std::runtime_error(
        fmt::format("cannot write '{}': {}", file.string(), std::strerror(errno)));
  return fd;
}

void write_all(int fd, std::string_view data, const std::filesystem::path& file) {
  const char* p = data.data();
  std::size_t left = data.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error(fmt::format("cannot write '{}': {}", file.string(),
                                           n < 0 ? std::strerror(errno) : "no space"));
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void write_file_atomically(const std::filesystem::path& file, std::string_view content) {
  write_file_atomically(file, std::span<const std::string_view>(&content, 1));
}

void write_file_atomically(const std::filesystem::path& file,
                           std::span<const std::string_view> parts) {
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  const int fd = open_for_writing(tmp, O_WRONLY | O_CREAT | O_TRUNC);
  try {
    for (const std::string_view part : parts) write_all(fd, part, tmp);
  } catch (...) {
    ::close(fd);
    throw;
  }
  const bool synced = ::fsync(fd) == 0;
  ::close(fd);
  std::error_code ec;
  if (synced) std::filesystem::rename(tmp, file, ec);
  if (!synced || ec)
    throw std::runtime_error(fmt::format("cannot replace '{}': {}", file.string(),
                                         synced ? ec.message() : std::strerror(errno)));
}

}  // namespace vorodec::io
