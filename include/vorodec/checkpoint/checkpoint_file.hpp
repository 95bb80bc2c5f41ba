#pragma once
// A checkpoint file: a magic string, the format version, the body's size and CRC-32, then the
// body: the header below (cereal binary), then the run's state (cereal binary archive). A file from
// another vorodec version, for another model file, truncated or corrupt is refused, and the error
// says which.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "vorodec/checkpoint/archive.hpp"

namespace vorodec::checkpoint {

// 3: the quasi-static driver saves its stage modes in turn (each its state and reports).
// 4: zone stresses and strains saved as arrays by component; the zone-force scratch is not saved.
// 5: blocks carry their groups (excavation).
// 6: excavation stages save their joint-set measures and relaxation loads.
// 7: the solver's energy terms hold the in-situ stress's initial strain energy.
// 8: zones saved as their gridpoints' displacements of the last force pass, not as stress and
//    strain arrays (computed from them when asked).
inline constexpr std::uint32_t kFormat = 8;

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
  std::string state;  // the run's state: read it with an InArchive
};

// Through a temporary name, synced, renamed over the last one: a kill keeps one whole checkpoint.
// `state` writes the run's state into the archive after the header (no copy of it is made).
// Returns the bytes of the state.
std::size_t write_checkpoint(const std::filesystem::path& file, const Header& header,
                             const std::function<void(OutArchive&)>& state);
// Throws CheckpointError: no such file, not a checkpoint, another format or vorodec version,
// truncated, corrupt.
Contents read_checkpoint(const std::filesystem::path& file);

// CRC-32 (zlib) of the files' contents and of the strings, in turn: what a model file resolves to.
std::uint32_t model_hash(const std::vector<std::filesystem::path>& files,
                         const std::vector<std::string>& strings);

}  // namespace vorodec::checkpoint
