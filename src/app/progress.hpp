#pragma once
// Progress of a run: a bar with ETA on a terminal, plain lines every 10 % otherwise.
#include <chrono>
#include <cstddef>

namespace vorodec::app {

class Progress {
 public:
  Progress(bool enabled, std::size_t stages);
  // `fraction` is the known progress of stage `stage` (0..1; 0 when it cannot be estimated).
  void update(std::size_t stage, double fraction, double stress, double peak, long steps);
  void finish();

 private:
  bool enabled_, tty_;
  std::size_t stages_;
  std::chrono::steady_clock::time_point start_, last_;
  int last_decile_ = -1;
  long calls_ = 0;
};

}  // namespace vorodec::app
