// Latency percentiles over a long run without keeping every sample: 10-microsecond bins up to
// 100 ms (larger values count in the last bin; the exact maximum is kept). Not thread-safe.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rle_vision {

class LatencyHistogram {
 public:
  static constexpr double kBinMs = 0.01;
  static constexpr int kBins = 10000;  // 0 .. 100 ms

  LatencyHistogram() : bins_(kBins, 0) {}

  void add(double ms) {
    if (!std::isfinite(ms)) return;
    ms = std::max(0.0, ms);
    // Compared as doubles: a huge value must not overflow the int conversion.
    const int bin = ms / kBinMs >= kBins - 1 ? kBins - 1 : static_cast<int>(ms / kBinMs);
    ++bins_[bin];
    ++count_;
    max_ms_ = std::max(max_ms_, ms);
  }

  uint64_t count() const { return count_; }
  // Samples above `ms` (to the bin: exact for multiples of kBinMs). Two readings of a running
  // histogram give the count over the time between them, so a window excludes the start-up.
  uint64_t countAbove(double ms) const {
    const int first = std::min(kBins, std::max(0, static_cast<int>(std::lround(ms / kBinMs))));
    uint64_t above = 0;
    for (int b = first; b < kBins; ++b) above += bins_[b];
    return above;
  }
  double maxMs() const { return max_ms_; }

  // The upper edge of the bin holding the p-th percentile (0 < p <= 100), so the value
  // reported is never below the true percentile; 0 when empty.
  double percentileMs(double p) const {
    if (count_ == 0) return 0.0;
    const uint64_t rank = std::max<uint64_t>(1, static_cast<uint64_t>(std::ceil(p / 100.0 * count_)));
    uint64_t seen = 0;
    for (int b = 0; b < kBins; ++b) {
      seen += bins_[b];
      if (seen >= rank) return b == kBins - 1 ? max_ms_ : std::min(max_ms_, (b + 1) * kBinMs);
    }
    return max_ms_;
  }

 private:
  std::vector<uint64_t> bins_;
  uint64_t count_ = 0;
  double max_ms_ = 0.0;
};

}  // namespace rle_vision
