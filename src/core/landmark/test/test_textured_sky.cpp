// A hazy ridge under a cloud-textured sky: the ridge's edge is fainter than the clouds' own, so
// the refinement against the sky's high edge values passes over it to the stronger step below;
// the second refinement, against the sky's typical edge values, puts a candidate on it.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "landmark/horizon_refine.h"
#include "rle_vision/landmark/horizon_finder.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {
namespace {

constexpr int kRidgeRow = 230;   // the labelled horizon: the top of the hazy ridge
constexpr int kForestRow = 250;  // the dark, textured ground starts here, 20 px lower

// Sharp-edged clouds (130 to 250 grey) that fade into a uniform haze (190) over the 40 rows
// above the ridge; a ridge 30 grey levels darker than the haze; a textured forest 50 darker
// again. Edge values: the sky's 95th percentile 75 (its median 6), the ridge 64, the forest's
// step 101 (so its typical maximum over 2 is under the ridge's).
cv::Mat texturedSkyFrame() {
  cv::Mat coarse(16, 20, CV_32F), clouds, grain(480, 640, CV_32F);
  cv::RNG rng(5);
  rng.fill(coarse, cv::RNG::NORMAL, 0.0, 1.0);
  cv::resize(coarse, clouds, cv::Size(640, 480), 0, 0, cv::INTER_CUBIC);
  rng.fill(grain, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(grain, grain, cv::Size(0, 0), 1.5);
  cv::Mat image(480, 640, CV_8UC3);
  for (int y = 0; y < image.rows; ++y) {
    const double cloud_weight = std::clamp((kRidgeRow - y) / 40.0, 0.0, 1.0);
    for (int x = 0; x < image.cols; ++x) {
      double v;
      if (y < kRidgeRow) {
        v = 190 + cloud_weight * 60 * std::tanh(4 * clouds.at<float>(y, x));
      } else if (y < kForestRow) {
        v = 160;
      } else {
        v = 110 + 20 * grain.at<float>(y, x);
      }
      image.at<cv::Vec3b>(y, x) =
          cv::Vec3b(cv::saturate_cast<uint8_t>(v + 10), cv::saturate_cast<uint8_t>(v), cv::saturate_cast<uint8_t>(v - 5));
    }
  }
  return image;
}

// The distance (px at the centre column) of the candidate nearest the level line y = row.
double nearestCandidate(const cv::Mat& image, int row, const HorizonOptions& horizon_options) {
  LandmarkDetector detector;
  LandmarkResult result;
  LandmarkOptions options;
  options.horizon = horizon_options;
  detector.detectInImage(image, options, &result);
  HorizonDetector horizons;
  const ImageLine level = lineThroughPoints(0, row, 1, row);
  double best = INFINITY;
  for (const HorizonEstimate& c : horizons.candidates(image, detector.edges(), options.edge_gain, result.lines, horizon_options)) {
    if (lineAngleDifference(c.line.theta, level.theta) > M_PI / 180) continue;  // within 1 deg of level
    best = std::min(best, std::fabs(signedDistance(c.line, image.cols / 2.0, row)));
  }
  return best;
}

TEST(TexturedSky, TheHazyRidgeGetsACandidateOfItsOwn) {
  const cv::Mat image = texturedSkyFrame();
  HorizonOptions once;  // the second refinement off
  once.textured_sky_percentile = once.sky_percentile;
  const HorizonOptions twice;  // the defaults
  ASSERT_LT(twice.textured_sky_percentile, twice.sky_percentile);
  const double ridge_once = nearestCandidate(image, kRidgeRow, once);
  const double ridge_twice = nearestCandidate(image, kRidgeRow, twice);
  std::printf("[ textured sky ] nearest candidate to the ridge: %.1f px refined once, %.1f px twice\n", ridge_once,
              ridge_twice);
  EXPECT_GT(ridge_once, 10.0);  // every refinement ended on the forest's step (20 px below)
  EXPECT_LT(ridge_twice, 2.0);
  // The first refinement's candidates stay: the forest's step is still one of them.
  EXPECT_LT(nearestCandidate(image, kForestRow, twice), 2.0);
}

TEST(TexturedSky, RefinementEndsWhenTheFirstLineIsTaken) {
  // One hypothesis between the ridge and the forest, refined against both percentiles: two
  // distinct lines; a sink that takes the first ends it there (the second not refined).
  const cv::Mat image = texturedSkyFrame();
  LandmarkDetector detector;
  LandmarkResult result;
  detector.detectInImage(image, LandmarkOptions(), &result);
  horizon::RegionGrid fine;
  fine.build(image, 8);
  horizon::HorizonRefiner refiner;
  refiner.sampleTexture(detector.edges(), fine);
  const horizon::Hypothesis between{0, 0.5 * (kRidgeRow + kForestRow) - image.rows / 2.0, 0};
  const horizon::RefineOptions options;
  std::vector<double> rows;
  auto refine = [&](bool take_first) {
    rows.clear();
    refiner.refineEach(detector.edges(), fine, between, options, {95, 50}, [&](const horizon::RefinedHorizon& r) {
      rows.push_back(r.line.rho / r.line.ny);  // the level line's row
      return take_first;
    });
  };
  refine(false);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_NEAR(rows[0], kForestRow, 2.0);  // the sky's high edge values: the forest's step
  EXPECT_NEAR(rows[1], kRidgeRow, 2.0);   // its typical ones: the hazy ridge
  refine(true);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0], kForestRow, 2.0);
}

}  // namespace
}  // namespace rle_vision
