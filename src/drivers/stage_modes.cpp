// The stage modes' table: a new mode is its two files and one row here.
#include <algorithm>
#include <array>

#include "corrosion_mode.hpp"
#include "creep_mode.hpp"
#include "excavation_mode.hpp"
#include "stage_mode.hpp"

namespace vorodec::run {

namespace {

struct ModeRow {
  io::StageModeKeys keys;
  std::unique_ptr<StageMode> (*make)(const DriverContext&);
};

template <class M>
std::unique_ptr<StageMode> make(const DriverContext& c) {
  return std::make_unique<M>(c);
}

// In this order their history columns follow each other, and their controls are listed in the
// model-file reader's messages.
constexpr std::array kModes{
    ModeRow{CreepMode::keys, make<CreepMode>},
    ModeRow{CorrosionMode::keys, make<CorrosionMode>},
    ModeRow{ExcavationMode::keys, make<ExcavationMode>},
};

constexpr auto kKeys = [] {
  std::array<io::StageModeKeys, kModes.size()> keys{};
  for (std::size_t i = 0; i < kModes.size(); ++i) keys[i] = kModes[i].keys;
  return keys;
}();

}  // namespace

std::vector<std::unique_ptr<StageMode>> make_stage_modes(const DriverContext& c) {
  std::vector<std::unique_ptr<StageMode>> modes;
  const auto& stages = c.cfg.load_path.stages;
  for (const ModeRow& row : kModes)
    if (std::any_of(stages.begin(), stages.end(),
                    [&](const loading::Stage& s) { return s.mode == row.keys.control; })) {
      modes.push_back(row.make(c));  // makes nothing happen until a stage begins
      modes.back()->control_ = row.keys.control;
    }
  return modes;
}

std::span<const io::StageModeKeys> stage_mode_keys() {
  return kKeys;
}

}  // namespace vorodec::run
