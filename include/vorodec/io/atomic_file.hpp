#pragma once
// Files a kill cannot leave half-written: whole writes, and whole files replaced by rename.
#include <filesystem>
#include <span>
#include <string_view>

namespace vorodec::io {

// A file descriptor for writing (O_CLOEXEC added); throws naming the file.
int open_for_writing(const std::filesystem::path& file, int flags);

// All of `data` to fd, retrying short writes; throws naming the file.
void write_all(int fd, std::string_view data, const std::filesystem::path& file);

// Writes `content` to `file` through a temporary name, synced and renamed over it: a reader
// (or a kill) sees the old file or the new one, never a part.
void write_file_atomically(const std::filesystem::path& file, std::string_view content);
// The same for content in parts, written one after the other.
void write_file_atomically(const std::filesystem::path& file,
                           std::span<const std::string_view> parts);

}  // namespace vorodec::io
