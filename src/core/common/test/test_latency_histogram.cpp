// The tracker's latency percentiles: known samples give known percentiles, within one 10-us bin
// and never below the true value.
#include <gtest/gtest.h>

#include <limits>

#include "rle_vision/common/latency_histogram.h"

namespace rle_vision {
namespace {

TEST(LatencyHistogram, PercentilesOfKnownSamples) {
  LatencyHistogram h;
  EXPECT_EQ(h.percentileMs(50), 0.0);
  // 1000 samples 0.001, 0.002, ..., 1.000 ms: p50 = 0.5 ms, p99 = 0.99 ms.
  for (int i = 1; i <= 1000; ++i) h.add(i * 0.001);
  EXPECT_EQ(h.count(), 1000u);
  EXPECT_GE(h.percentileMs(50), 0.5 - 1e-9);
  EXPECT_LE(h.percentileMs(50), 0.5 + LatencyHistogram::kBinMs);
  EXPECT_GE(h.percentileMs(99), 0.99 - 1e-9);
  EXPECT_LE(h.percentileMs(99), 0.99 + LatencyHistogram::kBinMs);
  EXPECT_DOUBLE_EQ(h.percentileMs(100), 1.0);
  EXPECT_DOUBLE_EQ(h.maxMs(), 1.0);
}

TEST(LatencyHistogram, CountsAboveABoundGiveAWindowsShare) {
  LatencyHistogram h;
  for (int i = 0; i < 50; ++i) h.add(0.4);  // start-up: 10 slow frames among 50
  for (int i = 0; i < 10; ++i) h.add(7.0);
  const uint64_t all_before = h.count(), over_before = h.countAbove(2.0);
  EXPECT_EQ(over_before, 10u);
  EXPECT_EQ(h.countAbove(0.4), 60u);  // a bound counts its own bin
  EXPECT_EQ(h.countAbove(0.41), 10u);
  for (int i = 0; i < 995; ++i) h.add(0.8);  // the window: 5 of 1000 over 2 ms
  for (int i = 0; i < 5; ++i) h.add(2.5);
  EXPECT_EQ(h.count() - all_before, 1000u);
  EXPECT_EQ(h.countAbove(2.0) - over_before, 5u);
  EXPECT_EQ(h.countAbove(500.0), 0u);  // beyond the range: the last bin only
  EXPECT_EQ(h.countAbove(-1.0), h.count());
}

TEST(LatencyHistogram, OutliersBeyondTheRangeKeepTheirMaximum) {
  LatencyHistogram h;
  for (int i = 0; i < 98; ++i) h.add(0.25);
  h.add(250.0);  // beyond the 100-ms range
  LatencyHistogram far;
  far.add(1.7e12);  // an image stamped decades ago: counted in the last bin, no overflow
  EXPECT_DOUBLE_EQ(far.percentileMs(50), 1.7e12);
  h.add(-1.0);   // clock skew: counts as 0
  h.add(std::numeric_limits<double>::quiet_NaN());  // ignored
  EXPECT_EQ(h.count(), 100u);
  for (double p : {50.0, 99.0}) {  // sorted: 0 (the clamped -1), 98 x 0.25, 250
    EXPECT_GE(h.percentileMs(p), 0.25);
    EXPECT_LE(h.percentileMs(p), 0.25 + LatencyHistogram::kBinMs + 1e-9);
  }
  EXPECT_DOUBLE_EQ(h.percentileMs(100), 250.0);
  EXPECT_DOUBLE_EQ(h.maxMs(), 250.0);
}

}  // namespace
}  // namespace rle_vision
