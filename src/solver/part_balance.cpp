#include "vorodec/solver/part_balance.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace vorodec::solver {

void PartBalance::reset(std::size_t ranges, int parts) {
  const auto k = static_cast<std::size_t>(std::max(parts, 1));
  ranges_.assign(ranges, Range{std::vector<double>(k, 1.0 / static_cast<double>(k)),
                               std::vector<std::size_t>(k + 1, 0), std::vector<laws::PartClock>(k),
                               std::vector<double>(k, 0.0), std::vector<double>(k, 0.0), 0});
  pinned_ = false;
}

void PartBalance::pin(std::vector<double> shares) {
  for (Range& r : ranges_) r.share = shares;
  pinned_ = true;
}

void PartBalance::rebalance() {
  for (Range& r : ranges_) {
    const std::size_t k = r.share.size();
    const long passes = r.passes;
    r.passes = 0;
    const std::vector<double> lag = std::exchange(r.lag, std::vector<double>(k, 0.0));
    const std::vector<double> busy = std::exchange(r.busy, std::vector<double>(k, 0.0));
    if (pinned_ || passes == 0 || k < 2) continue;
    // Part t runs rate[t] contacts per second after starting lag[t] late: equal finishing times
    // F give it rate[t] (F - lag[t]) contacts.
    std::vector<double> rate(k), mean_lag(k);
    double n = 0.0;
    bool measured = true;
    for (std::size_t t = 0; t < k; ++t) {
      const auto count = static_cast<double>(r.cuts[t + 1] - r.cuts[t]);
      measured = measured && count > 0.0 && busy[t] > 0.0;
      rate[t] = measured ? count * static_cast<double>(passes) / busy[t] : 0.0;
      mean_lag[t] = lag[t] / static_cast<double>(passes);
      n += count;
    }
    if (!measured) continue;
    const double sum_rate = std::accumulate(rate.begin(), rate.end(), 0.0);
    double finish = n;
    for (std::size_t t = 0; t < k; ++t) finish += rate[t] * mean_lag[t];
    finish /= sum_rate;
    std::vector<double> want(k);
    for (std::size_t t = 0; t < k; ++t) want[t] = std::max(0.0, rate[t] * (finish - mean_lag[t]));
    const double sum_want = std::accumulate(want.begin(), want.end(), 0.0);
    if (!(sum_want > 0.0)) continue;
    // Halfway, and no part below a quarter of an equal share: one noisy interval moves little.
    const double floor = 0.25 / static_cast<double>(k);
    double total = 0.0;
    for (std::size_t t = 0; t < k; ++t) {
      r.share[t] = std::max(floor, 0.5 * r.share[t] + 0.5 * want[t] / sum_want);
      total += r.share[t];
    }
    for (double& s : r.share) s /= total;
  }
}

const std::size_t* PartBalance::cut(std::size_t r, std::size_t begin, std::size_t end) {
  Range& range = ranges_[r];
  const std::size_t k = range.share.size();
  const auto n = static_cast<double>(end - begin);
  double sum = 0.0;
  range.cuts[0] = begin;
  for (std::size_t t = 0; t + 1 < k; ++t) {
    sum += range.share[t];
    const auto at = begin + static_cast<std::size_t>(std::llround(sum * n));
    range.cuts[t + 1] = std::clamp(at, range.cuts[t], end);
  }
  range.cuts[k] = end;
  return range.cuts.data();
}

void PartBalance::start(std::size_t r) {
  for (laws::PartClock& c : ranges_[r].clocks) c.end = -1.0;
}

void PartBalance::record(std::size_t r, double begin) {
  Range& range = ranges_[r];
  for (const laws::PartClock& c : range.clocks)
    if (c.end < 0.0) return;  // the pass ran on one thread
  for (std::size_t t = 0; t < range.clocks.size(); ++t) {
    range.lag[t] += range.clocks[t].start - begin;
    range.busy[t] += range.clocks[t].end - range.clocks[t].start;
  }
  ++range.passes;
}

}  // namespace vorodec::solver
