#include "vorodec/checkpoint/checkpoint_file.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/io/atomic_file.hpp"

namespace vorodec::checkpoint {

namespace {

constexpr char kMagic[16] = "vorodec-ckpt-v1";  // 15 characters and the terminating zero

std::uint32_t crc32_of(std::string_view data, std::uint32_t crc = 0) {
  // zlib takes lengths as uInt: large bodies go in parts.
  constexpr std::size_t part = 1u << 30;
  uLong c = crc;
  for (std::size_t at = 0; at < data.size(); at += part) {
    const std::size_t n = std::min(part, data.size() - at);
    c = ::crc32(c, reinterpret_cast<const Bytef*>(data.data() + at), static_cast<uInt>(n));
  }
  return static_cast<std::uint32_t>(c);
}

}  // namespace

std::size_t write_checkpoint(const std::filesystem::path& file, const Header& header,
                             const std::function<void(OutArchive&)>& state) {
  std::ostringstream out;
  std::size_t header_bytes = 0;
  {
    OutArchive ar(out);
    ar(header);
    header_bytes = static_cast<std::size_t>(out.tellp());
    state(ar);
  }
  const std::string body = std::move(out).str();
  std::ostringstream frame;
  {
    OutArchive ar(frame);
    ar(cereal::binary_data(kMagic, sizeof kMagic), kFormat, std::uint64_t{body.size()},
       crc32_of(body));
  }
  const std::string f = frame.str();
  const std::string_view parts[] = {f, body};
  io::write_file_atomically(file, parts);
  return body.size() - header_bytes;
}

Contents read_checkpoint(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CheckpointError(fmt::format("{}: no checkpoint there", name));
  const std::string all{std::istreambuf_iterator<char>(in), {}};
  constexpr std::size_t framing = sizeof kMagic + 4 + 8 + 4;
  const std::size_t head = std::min(all.size(), sizeof kMagic);
  if (head == 0 || all.compare(0, head, kMagic, head) != 0)
    throw CheckpointError(fmt::format("{}: not a vorodec checkpoint", name));
  if (all.size() < framing)
    throw CheckpointError(fmt::format("{}: truncated (only {} bytes)", name, all.size()));
  std::uint32_t format = 0, crc = 0;
  std::uint64_t size = 0;
  {
    std::istringstream frame(all.substr(sizeof kMagic, framing - sizeof kMagic));
    InArchive ar(frame);
    ar(format, size, crc);
  }
  if (format != kFormat)
    throw CheckpointError(
        fmt::format("{}: checkpoint format {}, this vorodec reads format {}: start the run again",
                    name, format, kFormat));
  if (all.size() - framing < size)
    throw CheckpointError(fmt::format("{}: truncated ({} of {} bytes): a write was cut short", name,
                                      all.size() - framing, size));
  const std::string_view body(all.data() + framing, static_cast<std::size_t>(size));
  if (all.size() - framing > size || crc32_of(body) != crc)
    throw CheckpointError(fmt::format("{}: corrupt (its checksum does not match)", name));
  Contents c;
  std::istringstream stream{std::string(body)};
  {
    InArchive ar(stream);
    ar(c.header);
  }
  c.state = body.substr(static_cast<std::size_t>(stream.tellg()));
  if (c.header.vorodec_version != VORODEC_VERSION)
    throw CheckpointError(
        fmt::format("{}: written by vorodec {}, this is vorodec {}: start the run again", name,
                    c.header.vorodec_version, VORODEC_VERSION));
  return c;
}

std::uint32_t model_hash(const std::vector<std::filesystem::path>& files,
                         const std::vector<std::string>& strings) {
  std::uint32_t crc = 0;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    crc = crc32_of(text, crc32_of(f.filename().string() + '\n', crc));
  }
  for (const auto& s : strings) crc = crc32_of(s + '\n', crc);
  return crc;
}

}  // namespace vorodec::checkpoint
