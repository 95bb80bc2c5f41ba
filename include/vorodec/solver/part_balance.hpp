#pragma once
// Where the contact passes' thread parts are cut. Equal counts of contacts do not take equal
// times: contacts differ in cost along the contact order, and the thread that also runs the
// serial work finds less of its data in its cache. Any cut gives the same bits
// (laws::StepContext), so the cuts follow the clock: each part's start and duration are summed
// over the passes between detections, and at each detection the cuts move halfway towards
// equal finishing times (docs/theory.md §5.7). The cuts set no result, so they are not part of a
// checkpoint: a resumed run starts from equal parts.
#include <cstddef>
#include <vector>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::solver {

class PartBalance {
 public:
  // `ranges` contact ranges, each cut into `parts` parts; starts from equal shares.
  void reset(std::size_t ranges, int parts);
  std::size_t ranges() const { return ranges_.size(); }
  // Fixes the shares of every range (one per part, each positive, summing to 1) and stops following
  // the clock: tests pin unequal parts with this.
  void pin(std::vector<double> shares);
  // Moves the shares towards equal finishing times over the passes recorded, then forgets them.
  void rebalance();
  // Cuts range r, [begin, end), by its shares; returns the parts + 1 cuts.
  const std::size_t* cut(std::size_t r, std::size_t begin, std::size_t end);
  const std::size_t* cuts(std::size_t r) const { return ranges_[r].cuts.data(); }
  laws::PartClock* clocks(std::size_t r) { return ranges_[r].clocks.data(); }
  // Before a pass of range r: marks its clocks unread.
  void start(std::size_t r);
  // After the pass, which began at `begin` (omp_get_wtime, s): adds each part's lag and duration
  // if every part ran in the parallel region.
  void record(std::size_t r, double begin);

 private:
  struct Range {
    std::vector<double> share;  // of the range's contacts, per part
    std::vector<std::size_t> cuts;
    std::vector<laws::PartClock> clocks;
    std::vector<double> lag, busy;  // s, summed over the passes recorded
    long passes = 0;
  };
  std::vector<Range> ranges_;
  bool pinned_ = false;
};

}  // namespace vorodec::solver
