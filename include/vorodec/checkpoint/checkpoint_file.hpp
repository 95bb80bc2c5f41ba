#pragma once
// A checkpoint file: a magic string, the format version, the body's size and CRC-32, then the
// body (cereal binary): the header below and the run's state. A file from another vorodec
// version, for another model file, truncated or corrupt is refused, and the error says which.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vorodec::checkpoint {

inline constexpr std::uint32_t kFormat = 1;

struct Header {
  std::string vorodec_version;
  std::string model_file;              // as `vorodec run` was given it
  std::vector<std::string> overrides;  // --set and batch overrides: key, value, origin in turn
  std::uint32_t model_hash = 0;        // model_hash() of the model file when the run started
  long max_steps = 0;                  // RunOptions
  bool write_vtk = true;
  long step = 0;            // solver steps done
  double time = 0;          // s, simulated
  double wall_seconds = 0;  // s, the run's wall time up to the checkpoint
  template <class Archive>
  void serialize(Archive& ar) {
    ar(vorodec_version, model_file, overrides, model_hash, max_steps, write_vtk, step, time,
       wall_seconds);
  }
};

class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Contents {
  Header header;
  std::string state;  // cereal binary archive of the run's state
};

// Through a temporary name, synced, renamed over the last one: a kill keeps one whole checkpoint.
void write_checkpoint(const std::filesystem::path& file, const Contents& contents);
// Throws CheckpointError: no such file, not a checkpoint, another format or vorodec version,
// truncated, corrupt.
Contents read_checkpoint(const std::filesystem::path& file);

// CRC-32 (zlib) of the files' contents and of the strings, in turn: what a model file resolves to.
std::uint32_t model_hash(const std::vector<std::filesystem::path>& files,
                         const std::vector<std::string>& strings);

}  // namespace vorodec::checkpoint
