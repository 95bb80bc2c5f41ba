// The stage modes' table: a new mode is its two files and one row here.
#include <algorithm>
#include <array>

#include "corrosion_mode.hpp"
#include "creep_mode.hpp"
#include "stage_mode.hpp"

namespace vorodec::run {

namespace {

template <class M>
std::unique_ptr<StageMode> make(const DriverContext& c) {
  return std::make_unique<M>(c);
}

// In this order their history columns follow each other.
constexpr std::array kModes{
    make<CreepMode>,
    make<CorrosionMode>,
};

}  // namespace

std::vector<std::unique_ptr<StageMode>> make_stage_modes(const DriverContext& c) {
  std::vector<std::unique_ptr<StageMode>> modes;
  for (const auto make_mode : kModes) {
    std::unique_ptr<StageMode> mode = make_mode(c);  // makes nothing happen until a stage begins
    const auto& stages = c.cfg.load_path.stages;
    if (std::any_of(stages.begin(), stages.end(),
                    [&](const loading::Stage& s) { return mode->runs(s); }))
      modes.push_back(std::move(mode));
  }
  return modes;
}

}  // namespace vorodec::run
