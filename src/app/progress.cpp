#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace vorodec::app {

Progress::Progress(bool enabled, std::size_t stages)
    : enabled_(enabled),
      tty_(isatty(STDERR_FILENO) != 0),
      stages_(std::max<std::size_t>(stages, 1)),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void Progress::update(std::size_t stage, double fraction, double stress, double peak, long steps) {
  if (!enabled_ || (++calls_ % 500) != 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double p =
      (static_cast<double>(stage) + std::clamp(fraction, 0.0, 1.0)) / static_cast<double>(stages_);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::string eta =
      p > 0.01 ? fmt::format("{:.0f} s", elapsed * (1.0 - p) / p) : std::string("?");
  if (tty_) {
    if (std::chrono::duration<double>(now - last_).count() < 0.2) return;
    last_ = now;
    const int width = 30, filled = static_cast<int>(p * width);
    fmt::print(
        stderr,
        "\r[{}{}] {:5.1f}%  stage {}/{}  step {}  stress {:.2f} MPa (peak {:.2f})  ETA {}   ",
        std::string(static_cast<std::size_t>(filled), '#'),
        std::string(static_cast<std::size_t>(width - filled), '.'), 100 * p, stage + 1, stages_,
        steps, stress / 1e6, peak / 1e6, eta);
  } else {
    const int decile = static_cast<int>(p * 10);
    if (decile == last_decile_) return;
    last_decile_ = decile;
    fmt::print(
        stderr,
        "progress {:3.0f}%  stage {}/{}  step {}  stress {:.2f} MPa  elapsed {:.0f} s  ETA {}\n",
        100 * p, stage + 1, stages_, steps, stress / 1e6, elapsed, eta);
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_ && tty_) fmt::print(stderr, "\n");
}

}  // namespace vorodec::app
