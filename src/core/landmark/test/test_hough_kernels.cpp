// The landmark step's inner loops against plain references: edge thinning against its rule
// pixel by pixel, the ridge profile's AVX2 kernel against the scalar one (bit for bit), the
// band's interval sort and merge, the unclaimed stretches of a row, and a run's closed-form
// sums against pixel by pixel.
#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "landmark/hough_band.h"
#include "landmark/ridge_profile.h"
#include "rle_vision/landmark/edge_objects.h"
#include "rle_vision/landmark/line_fit.h"

namespace rle_vision {
namespace {

using hough::Interval;

// thinEdges' rule written pixel by pixel: a pixel >= min_value stays where it is a maximum
// across the direction (of four) where 2 v - a - b is largest, the first on ties.
cv::Mat thinReference(const cv::Mat& e, uint8_t min_value) {
  cv::Mat out(e.size(), CV_8UC1, cv::Scalar(0));
  const int dx[4][2] = {{1, -1}, {0, 0}, {1, -1}, {1, -1}}, dy[4][2] = {{0, 0}, {1, -1}, {1, -1}, {-1, 1}};
  for (int y = 1; y + 1 < e.rows; ++y) {
    for (int x = 1; x + 1 < e.cols; ++x) {
      const int v = e.at<uint8_t>(y, x);
      int best = -1, best_curvature = 0;
      for (int d = 0; d < 4; ++d) {
        const int a = e.at<uint8_t>(y + dy[d][0], x + dx[d][0]), b = e.at<uint8_t>(y + dy[d][1], x + dx[d][1]);
        if (best < 0 || 2 * v - a - b > best_curvature) best = d, best_curvature = 2 * v - a - b;
      }
      const int a = e.at<uint8_t>(y + dy[best][0], x + dx[best][0]), b = e.at<uint8_t>(y + dy[best][1], x + dx[best][1]);
      if (v >= min_value && v >= a && v >= b) out.at<uint8_t>(y, x) = static_cast<uint8_t>(v);
    }
  }
  return out;
}

TEST(EdgeThinning, EqualsThePixelRuleWhereBlocksAreSmoothOrNot) {
  // Rows of strong and faint stretches of every length (the thinning skips 32-px stretches
  // without a pixel reaching min_value), at widths around the block size.
  std::mt19937 rng(11);
  for (const int width : {3, 31, 33, 64, 97, 640}) {
    cv::Mat edges(24, width, CV_8UC1);
    for (int y = 0; y < edges.rows; ++y) {
      for (int x = 0; x < width; ++x) {
        const bool strong = ((x + 7 * y) / 13) % 3 == 0;
        edges.at<uint8_t>(y, x) = static_cast<uint8_t>(strong ? rng() % 256 : rng() % 40);
      }
    }
    cv::Mat ours;
    thinEdges(edges, 40, &ours);
    EXPECT_EQ(cv::norm(ours, thinReference(edges, 40), cv::NORM_INF), 0.0) << "width " << width;
    EXPECT_GT(cv::countNonZero(ours), 0) << "width " << width;
  }
}

TEST(RidgeProfile, ScalarSamplesAreBilinear) {
  cv::Mat edges(4, 4, CV_8UC1, cv::Scalar(0));
  edges.at<uint8_t>(1, 1) = 100;
  edges.at<uint8_t>(1, 2) = 200;
  const double offset_x[] = {0.0, 0.5, 0.25, 0.0}, offset_y[] = {0.0, 0.0, 0.5, 0.5};
  double profile[4];
  ridge::profileInside(edges.data, edges.step, 1.0, 1.0, offset_x, offset_y, 4, profile);
  EXPECT_DOUBLE_EQ(profile[0], 100);                              // on the pixel
  EXPECT_DOUBLE_EQ(profile[1], 150);                              // halfway to its right neighbour
  EXPECT_DOUBLE_EQ(profile[2], 0.5 * (0.75 * 100 + 0.25 * 200));  // halfway down to a blank row
  EXPECT_DOUBLE_EQ(profile[3], 50);
}

#ifdef RLE_VISION_AVX2_KERNELS
TEST(RidgeProfile, Avx2KernelEqualsScalarBitForBit) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2";
  std::mt19937 rng(11);
  cv::Mat edges(61, 83, CV_8UC1);
  cv::randu(edges, 0, 256);
  std::uniform_real_distribution<double> unit(-1, 1), base_x(12, 70), base_y(12, 48);
  int checked = 0;
  for (int trial = 0; trial < 500; ++trial) {
    // Profiles of every length 1..23 (so every tail after the 4-wide steps) across a line
    // at a random angle, each sample's 2x2 neighbourhood inside the image.
    const int count = 1 + trial % 23;
    double nx = unit(rng), ny = unit(rng);
    const double norm = std::hypot(nx, ny) + 1e-9;
    nx /= norm;
    ny /= norm;
    std::vector<double> offset_x(count), offset_y(count);
    for (int k = 0; k < count; ++k) {
      offset_x[k] = (k - count / 2) * 0.5 * nx;
      offset_y[k] = (k - count / 2) * 0.5 * ny;
    }
    const double bx = base_x(rng), by = base_y(rng);
    std::vector<double> scalar(count), wide(count);
    ridge::profileInside(edges.data, edges.step, bx, by, offset_x.data(), offset_y.data(), count, scalar.data());
    ridge::profileInsideAvx2(edges.data, edges.step, bx, by, offset_x.data(), offset_y.data(), count, wide.data());
    ASSERT_EQ(0, std::memcmp(scalar.data(), wide.data(), count * sizeof(double))) << "trial " << trial;
    checked += count;
  }
  EXPECT_GT(checked, 5000);
}
#endif

std::vector<Interval> referencePieces(std::vector<Interval> list, double max_gap) {
  std::stable_sort(list.begin(), list.end(), [](const Interval& a, const Interval& b) { return a.t0 < b.t0; });
  // Each piece grows while the next interval starts within max_gap of its end.
  std::vector<Interval> out;
  for (size_t next = 0; next < list.size();) {
    Interval piece = list[next++];
    for (; next < list.size() && list[next].t0 <= piece.t1 + max_gap; ++next) {
      piece.t1 = std::max(piece.t1, list[next].t1);
      piece.pixels += list[next].pixels;
      piece.free_pixels += list[next].free_pixels;
    }
    out.push_back(piece);
  }
  return out;
}

TEST(HoughBand, PiecesOfRowsInEitherOrderEqualASortedMerge) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> stretch_count(1, 6), stretch_length(0, 12), start(-40, 40), gap(0, 6),
      width(0, 3), pixels(1, 5);
  for (int trial = 0; trial < 300; ++trial) {
    // Several stretches, each in order along the line one way or the other (a band's rows
    // walked top to bottom), as the Hough's band scans produce; t0 values may repeat.
    std::vector<Interval> list;
    const int stretches = stretch_count(rng);
    for (int s = 0; s < stretches; ++s) {
      std::vector<Interval> stretch;
      double t = start(rng);
      for (int k = stretch_length(rng); k > 0; --k) {
        const double w = width(rng);
        const double p = pixels(rng);
        stretch.push_back({t, t + w, p, p - (k % 2)});
        t += gap(rng);
      }
      if (rng() % 2) std::reverse(stretch.begin(), stretch.end());
      list.insert(list.end(), stretch.begin(), stretch.end());
    }
    std::vector<Interval> work = list;
    const std::vector<Interval> got = hough::pieces(&work, 2.0);
    const std::vector<Interval> want = referencePieces(list, 2.0);
    ASSERT_EQ(got.size(), want.size()) << "trial " << trial;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].t0, want[i].t0);
      EXPECT_EQ(got[i].t1, want[i].t1);
      EXPECT_EQ(got[i].pixels, want[i].pixels);
      EXPECT_EQ(got[i].free_pixels, want[i].free_pixels);
    }
    // And the input is left sorted, as pieces() promises.
    EXPECT_TRUE(std::is_sorted(work.begin(), work.end(), [](const Interval& a, const Interval& b) { return a.t0 < b.t0; }));
  }
}

TEST(HoughBand, PiecesSplitAtGapsWiderThanAllowed) {
  std::vector<Interval> list = {{20, 25, 6, 6}, {0, 4, 5, 5}, {6, 9, 4, 1}, {27, 30, 4, 4}};
  const std::vector<Interval> got = hough::pieces(&list, 2.0);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].t0, 0);
  EXPECT_EQ(got[0].t1, 9);
  EXPECT_EQ(got[0].pixels, 9);
  EXPECT_EQ(got[0].free_pixels, 6);
  EXPECT_EQ(got[1].t0, 20);
  EXPECT_EQ(got[1].t1, 30);
  EXPECT_EQ(got[1].pixels, 10);
}

TEST(HoughBand, UnclaimedStretchesOfARow) {
  //                        0  1  2  3  4  5  6  7  8  9
  const uint8_t claimed[] = {1, 0, 0, 1, 1, 0, 1, 0, 0, 0};
  std::vector<std::pair<int, int>> seen;
  hough::forEachUnclaimed(0, 9, claimed, [&](int a, int b) { seen.emplace_back(a, b); });
  EXPECT_EQ(seen, (std::vector<std::pair<int, int>>{{1, 2}, {5, 5}, {7, 9}}));
  seen.clear();
  hough::forEachUnclaimed(2, 6, claimed, [&](int a, int b) { seen.emplace_back(a, b); });
  EXPECT_EQ(seen, (std::vector<std::pair<int, int>>{{2, 2}, {5, 5}}));
  seen.clear();
  hough::forEachUnclaimed(3, 4, claimed, [&](int a, int b) { seen.emplace_back(a, b); });
  EXPECT_TRUE(seen.empty());
  hough::forEachUnclaimed(5, 4, claimed, [&](int a, int b) { seen.emplace_back(a, b); });  // empty range
  EXPECT_TRUE(seen.empty());
}

TEST(PointSums, RunSumsEqualPixelByPixel) {
  const int rows[] = {0, 7, -3, 611};
  const std::pair<int, int> runs[] = {{0, 0}, {3, 17}, {-5, 4}, {-9, -2}, {100, 799}, {-800, 800}};
  for (int y : rows) {
    for (const auto& run : runs) {
      PointSums closed, pixelwise;
      closed.addRun(run.first, run.second, y);
      for (int x = run.first; x <= run.second; ++x) pixelwise.addPixel(x, y);
      EXPECT_EQ(closed.n, pixelwise.n);
      EXPECT_EQ(closed.sx, pixelwise.sx);
      EXPECT_EQ(closed.sy, pixelwise.sy);
      EXPECT_EQ(closed.sxx, pixelwise.sxx) << run.first << ".." << run.second << " row " << y;
      EXPECT_EQ(closed.sxy, pixelwise.sxy);
      EXPECT_EQ(closed.syy, pixelwise.syy);
    }
  }
}

}  // namespace
}  // namespace rle_vision
