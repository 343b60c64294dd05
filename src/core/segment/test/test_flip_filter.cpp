// The run-length encoder's flip filter (flip_filter_px): short stretches between two of one
// label take that label, so sensor noise neither cuts runs nor makes specks.
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rle_vision/segment/regions.h"
#include "rle_vision/segment/run_length.h"

namespace rle_vision {
namespace {

struct Stretch {
  int x0, x1;
  uint8_t label;
};

// The filter written plainly on the row's stretches: the first stretch that is short and lies
// between two of one label merges with them, then the search goes on from the merged one.
std::vector<rle_vision::Run> referenceFilteredRuns(const std::vector<uint8_t>& row, int y, int max_flip_px) {
  std::vector<Stretch> stretches;
  for (int x = 0; x < static_cast<int>(row.size()); ++x) {
    if (x == 0 || row[x] != row[x - 1]) stretches.push_back({x, x, row[x]});
    stretches.back().x1 = x;
  }
  for (size_t i = 1; i + 1 < stretches.size();) {
    const Stretch& middle = stretches[i];
    if (middle.x1 - middle.x0 + 1 <= max_flip_px && stretches[i - 1].label == stretches[i + 1].label) {
      stretches[i - 1].x1 = stretches[i + 1].x1;
      stretches.erase(stretches.begin() + static_cast<long>(i), stretches.begin() + static_cast<long>(i) + 2);
    } else {
      ++i;
    }
  }
  std::vector<rle_vision::Run> runs;
  for (const Stretch& s : stretches) {
    if (s.label != 0) runs.push_back(rle_vision::Run{s.x0, s.x1, y, static_cast<int32_t>(runs.size()), s.label});
  }
  return runs;
}

void expectRuns(const std::vector<rle_vision::Run>& runs, const std::vector<Stretch>& expected) {
  ASSERT_EQ(runs.size(), expected.size());
  for (size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(runs[i].x0, expected[i].x0) << "run " << i;
    EXPECT_EQ(runs[i].x1, expected[i].x1) << "run " << i;
    EXPECT_EQ(runs[i].label, expected[i].label) << "run " << i;
    EXPECT_EQ(runs[i].parent, static_cast<int32_t>(i));
  }
}

TEST(FlipFilter, FillsShortStretchesBetweenTwoOfOneLabel) {
  //                           0  1  2  3  4  5  6  7  8  9 10 11 12 13 14 15 16
  const std::vector<uint8_t> row{1, 1, 1, 0, 1, 1, 2, 2, 0, 0, 0, 3, 0, 0, 0, 1, 1};
  std::vector<rle_vision::Run> runs;
  appendRowRuns(row.data(), static_cast<int>(row.size()), 2, &runs, 1);
  // The background pixel inside the 1s is filled, the speck of 3 dropped, the 2s (between a 1
  // and background) and the row's last stretch kept.
  expectRuns(runs, {{0, 5, 1}, {6, 7, 2}, {15, 16, 1}});
  runs.clear();
  appendRowRuns(row.data(), static_cast<int>(row.size()), 2, &runs, 0);
  EXPECT_EQ(runs.size(), 5u);  // off: every labelled stretch is a run

  // A row's first and last stretches have one neighbour only: never relabelled, however short.
  const std::vector<uint8_t> ends{3, 0, 0, 0, 1, 0, 0, 2};
  runs.clear();
  appendRowRuns(ends.data(), static_cast<int>(ends.size()), 2, &runs, 1);
  expectRuns(runs, {{0, 0, 3}, {7, 7, 2}});

  const std::vector<uint8_t> pair{2, 2, 2, 1, 1, 2, 2, 2, 0, 0, 0};
  runs.clear();
  appendRowRuns(pair.data(), static_cast<int>(pair.size()), 0, &runs, 1);
  expectRuns(runs, {{0, 2, 2}, {3, 4, 1}, {5, 7, 2}});
  runs.clear();
  appendRowRuns(pair.data(), static_cast<int>(pair.size()), 0, &runs, 2);  // 4:2:2 flips come in pairs
  expectRuns(runs, {{0, 7, 2}});
}

// Rows from sparse to every pixel its own draw, and rows of short stretches only (chains of
// candidates, where every other one is joined), of every width around the 32- and 64-pixel
// words the encoder works in. appendRowRuns' encoder takes the word-parallel way for a row
// after a noisy row (on AVX2 CPUs), the per-start way otherwise: the rows below alternate, so
// both run, and both must give the plain filter's runs.
std::vector<uint8_t> randomRow(std::mt19937* rng, int width, int change_per_mille, int max_stretch_px,
                               int label_count) {
  std::vector<uint8_t> row(width);
  int left_in_stretch = 0;
  for (int x = 0; x < width; ++x) {
    bool change = x == 0;
    if (max_stretch_px > 0) {
      change = change || left_in_stretch == 0;
      if (change) left_in_stretch = 1 + static_cast<int>((*rng)() % static_cast<unsigned>(max_stretch_px));
      --left_in_stretch;
    } else {
      change = change || static_cast<int>((*rng)() % 1000) < change_per_mille;
    }
    row[x] = change ? static_cast<uint8_t>((*rng)() % static_cast<unsigned>(label_count)) : row[x - 1];
  }
  return row;
}

void expectPlainFilterRuns(const std::vector<uint8_t>& row, int max_flip_px, const std::string& what) {
  const int width = static_cast<int>(row.size());
  // Appended after the runs of earlier rows: each run's parent is its own index.
  std::vector<rle_vision::Run> runs(3, rle_vision::Run{0, 0, 4, 0, 1});
  appendRowRuns(row.data(), width, 5, &runs, max_flip_px);
  const std::vector<rle_vision::Run> expected = referenceFilteredRuns(row, 5, max_flip_px);
  ASSERT_EQ(runs.size(), expected.size() + 3) << what;
  for (size_t i = 0; i < expected.size(); ++i) {
    const rle_vision::Run& run = runs[i + 3];
    ASSERT_EQ(run.x0, expected[i].x0) << what << " run " << i;
    ASSERT_EQ(run.x1, expected[i].x1) << what << " run " << i;
    ASSERT_EQ(run.label, expected[i].label) << what << " run " << i;
    ASSERT_EQ(run.y, 5);
    ASSERT_EQ(run.parent, static_cast<int32_t>(i + 3));
  }
}

TEST(FlipFilter, EqualsThePlainFilterOnRandomRows) {
  std::mt19937 rng(11);
  for (int width : {1, 2, 3, 7, 8, 9, 31, 32, 33, 63, 64, 65, 100, 127, 128, 129, 640, 641}) {
    for (int max_flip_px : {1, 2, 3, 4, 5, 6, 7, 8}) {
      for (int trial = 0; trial < 6; ++trial) {
        for (int change_per_mille : {0, 30, 100, 400, 1000}) {
          const std::vector<uint8_t> row = randomRow(&rng, width, change_per_mille, 0, 3);
          expectPlainFilterRuns(row, max_flip_px, "width " + std::to_string(width) + " flip " +
                                                      std::to_string(max_flip_px) + " per mille " +
                                                      std::to_string(change_per_mille));
        }
        for (int max_stretch_px : {1, max_flip_px, max_flip_px + 1, 2 * max_flip_px + 2}) {
          const std::vector<uint8_t> row = randomRow(&rng, width, 0, max_stretch_px, 2 + trial % 2);
          expectPlainFilterRuns(row, max_flip_px, "width " + std::to_string(width) + " flip " +
                                                      std::to_string(max_flip_px) + " stretches up to " +
                                                      std::to_string(max_stretch_px));
        }
      }
    }
  }
  // Every label value a row may hold, 0 to 255.
  const std::vector<uint8_t> many = randomRow(&rng, 640, 0, 3, 256);
  expectPlainFilterRuns(many, 2, "labels 0-255");
}

// One encoder over an image whose rows go from clean to noisy and back, as a camera's do: a row
// after a noisy one is worked on 64 pixels at a time, a row after a clean one stretch by
// stretch, and whichever way a row goes, its runs are the plain filter's.
TEST(FlipFilter, OneEncoderOverCleanAndNoisyRowsGivesThePlainFiltersRuns) {
  std::mt19937 rng(23);
  for (int max_flip_px : {1, 2, 4}) {
    RowRunEncoder encoder;
    for (int y = 0; y < 60; ++y) {
      const int per_mille = (y / 5) % 3 == 0 ? 5 : ((y / 5) % 3 == 1 ? 300 : 1000);
      const std::vector<uint8_t> row = randomRow(&rng, 200 + y, per_mille, 0, 3);
      std::vector<rle_vision::Run> runs;
      encoder.append(row.data(), static_cast<int>(row.size()), y, &runs, max_flip_px);
      const std::vector<rle_vision::Run> expected = referenceFilteredRuns(row, y, max_flip_px);
      ASSERT_EQ(runs.size(), expected.size()) << "row " << y << " flip " << max_flip_px;
      for (size_t i = 0; i < expected.size(); ++i) {
        ASSERT_EQ(runs[i].x0, expected[i].x0) << "row " << y << " run " << i;
        ASSERT_EQ(runs[i].x1, expected[i].x1) << "row " << y << " run " << i;
        ASSERT_EQ(runs[i].label, expected[i].label) << "row " << y << " run " << i;
      }
    }
  }
}

// A ball (label 1) on background, with salt of another class around it and single-pixel holes
// in it, none two in a row and none next to the ball's edge (there the ball's last pixel would
// itself be a short stretch, between background and the hole, and go first): filtered, the ball
// is one region, exactly the clean ball filtered, and nothing else is left; unfiltered, the salt
// and holes make hundreds of regions.
TEST(FlipFilter, SaltAndHolesLeaveOneExactRegion) {
  cv::Mat clean = cv::Mat::zeros(120, 160, CV_8UC1);
  cv::circle(clean, {80, 60}, 30, cv::Scalar(1), cv::FILLED);
  cv::Mat noisy = clean.clone();
  std::mt19937 rng(5);
  for (int y = 0; y < noisy.rows; ++y) {
    for (int x = 2; x + 2 < noisy.cols; x += 3) {  // every third pixel at most: no two in a row
      if (rng() % 4 != 0) continue;
      uint8_t& p = noisy.at<uint8_t>(y, x);
      const bool inside = clean.at<uint8_t>(y, x - 2) == 1 && clean.at<uint8_t>(y, x + 2) == 1;
      const bool outside = clean.at<uint8_t>(y, x - 1) == 0 && clean.at<uint8_t>(y, x + 1) == 0;
      if (inside) p = 0;
      if (outside) p = 2;
    }
  }
  auto regionsOf = [](const cv::Mat& labels, int max_flip_px) {
    std::vector<rle_vision::Run> runs;
    std::vector<int32_t> row_starts;
    for (int y = 0; y < labels.rows; ++y) {
      row_starts.push_back(static_cast<int32_t>(runs.size()));
      appendRowRuns(labels.ptr<uint8_t>(y), labels.cols, y, &runs, max_flip_px);
    }
    row_starts.push_back(static_cast<int32_t>(runs.size()));
    RegionBuilder builder;
    std::vector<Region> regions;
    builder.build(&runs, row_starts, Connectivity::Eight, {}, &regions);
    return regions;
  };
  const std::vector<Region> filtered = regionsOf(noisy, 1);
  ASSERT_EQ(filtered.size(), 1u);
  EXPECT_EQ(filtered[0].label, 1);
  // Exactly the clean ball filtered: that loses only the circle's one-pixel tips, top and bottom.
  const std::vector<Region> clean_filtered = regionsOf(clean, 1);
  ASSERT_EQ(clean_filtered.size(), 1u);
  EXPECT_EQ(filtered[0].area, clean_filtered[0].area);
  EXPECT_EQ(filtered[0].area + 2, static_cast<uint32_t>(cv::countNonZero(clean)));
  EXPECT_NEAR(filtered[0].cx, 80.0, 1e-9);
  EXPECT_NEAR(filtered[0].cy, 60.0, 1e-9);
  EXPECT_GT(regionsOf(noisy, 0).size(), 100u);
}

}  // namespace
}  // namespace rle_vision
