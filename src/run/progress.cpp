#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace vorodec::run {

Progress::Progress(bool enabled, std::function<void(const ProgressReport&)> callback)
    : enabled_(enabled),
      tty_(isatty(STDERR_FILENO) != 0),
      callback_(std::move(callback)),
      start_(Clock::now()),
      last_(start_),
      stage_start_(start_) {}

void Progress::show(const ProgressReport& r) {
  if (callback_) callback_(r);
  if (!enabled_) return;
  const auto now = Clock::now();
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  const bool new_stage = r.stage != stage_;
  if (new_stage) {
    stage_ = r.stage;
    stage_start_ = now;
    decile_ = -1;
  }
  const bool known = !std::isnan(r.fraction);
  const double f = known ? std::clamp(r.fraction, 0.0, 1.0) : 0.0;
  std::string what;
  if (known) {
    const double in_stage = seconds(now - stage_start_);
    // An ETA once a twentieth of the stage has run: before that it says more noise than time.
    const std::string eta =
        f > 0.05 ? fmt::format("ETA {:.0f} s", in_stage * (1.0 - f) / f) : std::string("ETA ?");
    what = fmt::format("{:5.1f}% of the stage  {}", 100 * f, eta);
  } else {
    what = r.waiting;
  }
  if (!r.clock.empty()) what = r.clock + "  " + what;
  const std::string line =
      fmt::format("stage {}/{} {}  step {}  stress {:.2f} MPa  {}", r.stage + 1, r.stages,
                  r.stage_name, r.steps, r.stress / 1e6, what);
  if (tty_) {
    if (!new_stage && seconds(now - last_) < 0.2) return;
    fmt::print(stderr, "\r{:<110}", line);
    drawn_ = true;
  } else {
    const int decile = known ? static_cast<int>(10 * f) : -1;
    const bool step_on = known && decile > decile_;
    if (!new_stage && !step_on && seconds(now - last_) < 30.0) return;
    decile_ = std::max(decile_, decile);
    fmt::print(stderr, "progress: {}  elapsed {:.0f} s\n", line, seconds(now - start_));
  }
  last_ = now;
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_ && tty_ && drawn_) fmt::print(stderr, "\n");
}

}  // namespace vorodec::run
