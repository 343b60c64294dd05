// Run-length encoding and union-find regions against a brute-force flood fill.
#include <cmath>
#include <queue>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rle_vision/segment/regions.h"
#include "rle_vision/segment/run_length.h"

namespace rle_vision {
namespace {

// Pixel-by-pixel breadth-first flood fill; regions in raster order of their first pixel.
// `pixels`, when given, receives each region's pixels.
std::vector<Region> floodFillRegions(const cv::Mat& labels, Connectivity connectivity,
                                     std::vector<std::vector<cv::Point>>* pixels = nullptr) {
  cv::Mat seen = cv::Mat::zeros(labels.size(), CV_8UC1);
  std::vector<Region> regions;
  for (int y0 = 0; y0 < labels.rows; ++y0) {
    for (int x0 = 0; x0 < labels.cols; ++x0) {
      const uint8_t label = labels.at<uint8_t>(y0, x0);
      if (label == 0 || seen.at<uint8_t>(y0, x0)) continue;
      double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      Region r;
      r.label = label;
      r.left = r.right = x0;
      r.top = r.bottom = y0;
      std::queue<cv::Point> queue;
      std::vector<cv::Point> members;
      queue.push({x0, y0});
      seen.at<uint8_t>(y0, x0) = 1;
      while (!queue.empty()) {
        const cv::Point p = queue.front();
        queue.pop();
        members.push_back(p);
        n += 1;
        sx += p.x;
        sy += p.y;
        sxx += double(p.x) * p.x;
        syy += double(p.y) * p.y;
        sxy += double(p.x) * p.y;
        r.left = std::min(r.left, p.x);
        r.right = std::max(r.right, p.x);
        r.top = std::min(r.top, p.y);
        r.bottom = std::max(r.bottom, p.y);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || (connectivity == Connectivity::Four && dx != 0 && dy != 0)) continue;
            const cv::Point q(p.x + dx, p.y + dy);
            if (q.x < 0 || q.y < 0 || q.x >= labels.cols || q.y >= labels.rows) continue;
            if (labels.at<uint8_t>(q) != label || seen.at<uint8_t>(q)) continue;
            seen.at<uint8_t>(q) = 1;
            queue.push(q);
          }
        }
      }
      r.area = static_cast<uint32_t>(n);
      r.cx = sx / n;
      r.cy = sy / n;
      r.var_xx = sxx / n - r.cx * r.cx;
      r.var_yy = syy / n - r.cy * r.cy;
      r.var_xy = sxy / n - r.cx * r.cy;
      regions.push_back(r);
      if (pixels) pixels->push_back(std::move(members));
    }
  }
  return regions;
}

std::vector<Region> rleRegions(const cv::Mat& labels, Connectivity connectivity,
                               std::vector<uint32_t> min_area = {}) {
  std::vector<const uint8_t*> rows;
  for (int y = 0; y < labels.rows; ++y) rows.push_back(labels.ptr<uint8_t>(y));
  std::vector<rle_vision::Run> runs;
  std::vector<int32_t> row_starts;
  encodeLabelRows(rows.data(), labels.cols, labels.rows, &runs, &row_starts);
  RegionBuilder builder;
  std::vector<Region> regions;
  builder.build(&runs, row_starts, connectivity, min_area, &regions);
  return regions;
}

void expectSameRegions(const cv::Mat& labels, Connectivity connectivity, const std::string& what) {
  std::vector<std::vector<cv::Point>> pixels;
  const std::vector<Region> expected = floodFillRegions(labels, connectivity, &pixels);
  const std::vector<Region> actual = rleRegions(labels, connectivity);
  ASSERT_EQ(actual.size(), expected.size()) << what;
  for (size_t i = 0; i < expected.size(); ++i) {
    const Region& e = expected[i];
    const Region& a = actual[i];
    ASSERT_EQ(a.label, e.label) << what << " region " << i;
    ASSERT_EQ(a.area, e.area) << what << " region " << i;
    ASSERT_EQ(a.left, e.left) << what;
    ASSERT_EQ(a.right, e.right) << what;
    ASSERT_EQ(a.top, e.top) << what;
    ASSERT_EQ(a.bottom, e.bottom) << what;
    ASSERT_NEAR(a.cx, e.cx, 1e-9) << what;
    ASSERT_NEAR(a.cy, e.cy, 1e-9) << what;
    ASSERT_NEAR(a.var_xx, e.var_xx, 1e-6) << what;
    ASSERT_NEAR(a.var_yy, e.var_yy, 1e-6) << what;
    ASSERT_NEAR(a.var_xy, e.var_xy, 1e-6) << what;
    ASSERT_GT(a.angle, -M_PI / 2) << what;
    ASSERT_LE(a.angle, M_PI / 2) << what;
    // The lowest pixel of this region in its centroid's column, found pixel by pixel (the
    // region's own cx picks the column: a last-bit difference must not pick another one).
    const int column = static_cast<int>(std::lround(a.cx));
    int bottom_at_cx = -1;
    for (const cv::Point& p : pixels[i]) {
      if (p.x == column) bottom_at_cx = std::max(bottom_at_cx, p.y);
    }
    if (bottom_at_cx < 0) bottom_at_cx = e.bottom;
    ASSERT_EQ(a.bottom_at_cx, bottom_at_cx) << what << " region " << i;
  }
}

cv::Mat randomLabels(int rows, int cols, int classes, double background, std::mt19937* rng) {
  cv::Mat labels(rows, cols, CV_8UC1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> label(1, classes);
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      labels.at<uint8_t>(y, x) = unit(*rng) < background ? 0 : static_cast<uint8_t>(label(*rng));
    }
  }
  return labels;
}

// Pixel by pixel: the runs of one row.
std::vector<Run> referenceRuns(const std::vector<uint8_t>& row, int y) {
  std::vector<Run> runs;
  for (size_t x = 0; x < row.size();) {
    size_t end = x;
    while (end < row.size() && row[end] == row[x]) ++end;
    if (row[x] != 0) {
      runs.push_back(Run{static_cast<int32_t>(x), static_cast<int32_t>(end - 1), y,
                         static_cast<int32_t>(runs.size()), row[x]});
    }
    x = end;
  }
  return runs;
}

TEST(RunLength, EqualsPixelByPixelOnRandomRows) {
  // Every width up to 100 (the 32- and 8-label steps and their tails) and noisy to smooth rows.
  std::mt19937 rng(3);
  for (int width = 1; width <= 100; ++width) {
    for (int change_per_mille : {0, 20, 300, 1000}) {
      std::vector<uint8_t> row(width);
      for (int x = 0; x < width; ++x) {
        const bool change = x == 0 || static_cast<int>(rng() % 1000) < change_per_mille;
        row[x] = change ? static_cast<uint8_t>(rng() % 4) : row[x - 1];
      }
      std::vector<rle_vision::Run> runs;
      appendRowRuns(row.data(), width, 7, &runs);
      const std::vector<rle_vision::Run> expected = referenceRuns(row, 7);
      ASSERT_EQ(runs.size(), expected.size()) << "width " << width;
      for (size_t i = 0; i < runs.size(); ++i) {
        ASSERT_EQ(runs[i].x0, expected[i].x0) << "width " << width << " run " << i;
        ASSERT_EQ(runs[i].x1, expected[i].x1);
        ASSERT_EQ(runs[i].y, 7);
        ASSERT_EQ(runs[i].label, expected[i].label);
        ASSERT_EQ(runs[i].parent, static_cast<int32_t>(i));
      }
    }
  }
}

TEST(RunLength, EncodesKnownRow) {
  const uint8_t row[] = {0, 1, 1, 0, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 1, 0, 0, 3};
  std::vector<rle_vision::Run> runs;
  appendRowRuns(row, sizeof(row), 4, &runs);
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_EQ(runs[0].x0, 1);
  EXPECT_EQ(runs[0].x1, 2);
  EXPECT_EQ(runs[1].x0, 4);
  EXPECT_EQ(runs[1].x1, 13);  // crosses the 8-byte fast path
  EXPECT_EQ(runs[1].label, 2);
  EXPECT_EQ(runs[2].x0, 14);
  EXPECT_EQ(runs[2].x1, 14);
  EXPECT_EQ(runs[3].x0, 17);
  EXPECT_EQ(runs[3].label, 3);
  for (size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(runs[i].y, 4);
    EXPECT_EQ(runs[i].parent, static_cast<int32_t>(i));
  }
}

TEST(Regions, MatchFloodFillOnRandomImagesOfManySizes) {
  std::mt19937 rng(2024);
  const std::vector<cv::Size> sizes = {{1, 1}, {1, 17}, {17, 1}, {2, 2}, {640, 1}, {1, 480},
                                       {8, 8}, {9, 13}, {31, 7}, {64, 48}, {100, 3}, {200, 150}};
  for (const cv::Size& size : sizes) {
    for (int classes : {1, 2, 5}) {
      for (double background : {0.0, 0.3, 0.7}) {
        const cv::Mat labels = randomLabels(size.height, size.width, classes, background, &rng);
        for (Connectivity c : {Connectivity::Four, Connectivity::Eight}) {
          expectSameRegions(labels, c,
                            std::to_string(size.width) + "x" + std::to_string(size.height) +
                                " classes=" + std::to_string(classes) + " bg=" + std::to_string(background) +
                                " conn=" + std::to_string(static_cast<int>(c)));
        }
      }
    }
  }
}

TEST(Regions, BlobbyRandomImagesMatchFloodFill) {
  // Smoothed noise gives large irregular regions with holes, the shapes runs merge across.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    cv::Mat noise(120, 160, CV_32F);
    cv::RNG(trial).fill(noise, cv::RNG::UNIFORM, 0, 1);
    cv::Mat small = randomLabels(12, 16, 3, 0.4, &rng);
    cv::Mat labels;
    cv::resize(small, labels, cv::Size(160, 120), 0, 0, cv::INTER_NEAREST);
    for (int y = 0; y < labels.rows; ++y) {
      for (int x = 0; x < labels.cols; ++x) {
        if (noise.at<float>(y, x) < 0.05f) labels.at<uint8_t>(y, x) = 0;
      }
    }
    expectSameRegions(labels, Connectivity::Four, "blobby 4");
    expectSameRegions(labels, Connectivity::Eight, "blobby 8");
  }
}

TEST(Regions, AllOneClassIsOneRegion) {
  const cv::Mat labels(37, 53, CV_8UC1, cv::Scalar(3));
  const std::vector<Region> regions = rleRegions(labels, Connectivity::Eight);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].area, 37u * 53u);
  EXPECT_DOUBLE_EQ(regions[0].cx, 26.0);
  EXPECT_DOUBLE_EQ(regions[0].cy, 18.0);
  EXPECT_NEAR(regions[0].var_xx, (53.0 * 53.0 - 1) / 12.0, 1e-6);  // variance of 0..52
  EXPECT_NEAR(regions[0].angle, 0.0, 1e-12);  // wider than tall: major axis horizontal
  expectSameRegions(labels, Connectivity::Four, "uniform");
}

TEST(Regions, CheckerboardSplitsWithFourAndJoinsWithEightConnectivity) {
  cv::Mat labels(16, 16, CV_8UC1);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) labels.at<uint8_t>(y, x) = static_cast<uint8_t>(1 + (x + y) % 2);
  }
  EXPECT_EQ(rleRegions(labels, Connectivity::Four).size(), 256u);
  const std::vector<Region> eight = rleRegions(labels, Connectivity::Eight);
  ASSERT_EQ(eight.size(), 2u);  // each colour is diagonally connected
  EXPECT_EQ(eight[0].area, 128u);
  EXPECT_EQ(eight[1].area, 128u);
  expectSameRegions(labels, Connectivity::Four, "checkerboard 4");
  expectSameRegions(labels, Connectivity::Eight, "checkerboard 8");
  // A checkerboard with background squares: labelled pixels touch only at corners.
  cv::Mat sparse = labels.clone();
  sparse.setTo(0, labels == 2);
  EXPECT_EQ(rleRegions(sparse, Connectivity::Four).size(), 128u);
  EXPECT_EQ(rleRegions(sparse, Connectivity::Eight).size(), 1u);
}

TEST(Regions, DiagonalLineOrientation) {
  cv::Mat labels = cv::Mat::zeros(50, 50, CV_8UC1);
  for (int i = 0; i < 50; ++i) labels.at<uint8_t>(i, i) = 1;
  const std::vector<Region> eight = rleRegions(labels, Connectivity::Eight);
  ASSERT_EQ(eight.size(), 1u);
  EXPECT_NEAR(eight[0].angle, M_PI / 4, 1e-9);  // y down: descending to the right is +45 deg
  EXPECT_EQ(rleRegions(labels, Connectivity::Four).size(), 50u);
}

TEST(Regions, MinAreaDropsSmallRegionsPerLabel) {
  cv::Mat labels = cv::Mat::zeros(20, 20, CV_8UC1);
  labels(cv::Rect(0, 0, 3, 3)).setTo(1);    // 9 px of label 1
  labels(cv::Rect(10, 10, 2, 2)).setTo(1);  // 4 px of label 1
  labels(cv::Rect(15, 0, 2, 2)).setTo(2);   // 4 px of label 2
  const std::vector<Region> regions = rleRegions(labels, Connectivity::Eight, {0, 5, 1});
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].area, 9u);
  EXPECT_EQ(regions[1].label, 2);
}

TEST(Regions, EveryRunPointsAtItsRegionRoot) {
  std::mt19937 rng(3);
  const cv::Mat labels = randomLabels(40, 40, 2, 0.5, &rng);
  std::vector<const uint8_t*> rows;
  for (int y = 0; y < labels.rows; ++y) rows.push_back(labels.ptr<uint8_t>(y));
  std::vector<rle_vision::Run> runs;
  std::vector<int32_t> row_starts;
  encodeLabelRows(rows.data(), labels.cols, labels.rows, &runs, &row_starts);
  RegionBuilder builder;
  std::vector<Region> regions;
  builder.build(&runs, row_starts, Connectivity::Eight, {}, &regions);
  std::vector<uint32_t> area(runs.size(), 0);
  for (const rle_vision::Run& run : runs) {
    ASSERT_EQ(runs[run.parent].parent, run.parent);  // parent is a root
    area[run.parent] += run.length();
  }
  for (const Region& r : regions) EXPECT_EQ(area[r.root_run], r.area);
}

}  // namespace
}  // namespace rle_vision
