#pragma once
// Progress of a run for a person: on a terminal a line redrawn in place, otherwise a line at each
// stage, each tenth of a stage and every 30 s. Percentages never go back: a stage whose end is
// known ahead shows its own fraction (and an ETA for the stage); one that waits for a post-peak
// condition says what it waits for instead.
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

#include "vorodec/engine/driver.hpp"

namespace vorodec::run {

class Progress {
 public:
  // `enabled`: the line on stderr; `callback`: given every report.
  Progress(bool enabled, std::function<void(const ProgressReport&)> callback);
  // Whether to ask the driver for a report now (one call in 500 at most).
  bool due() { return (enabled_ || callback_) && ++calls_ % 500 == 0; }
  void show(const ProgressReport& r);
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_, tty_;
  std::function<void(const ProgressReport&)> callback_;
  Clock::time_point start_, last_, stage_start_;
  std::size_t stage_ = static_cast<std::size_t>(-1);
  int decile_ = -1;
  long calls_ = 0;
  bool drawn_ = false;
};

}  // namespace vorodec::run
