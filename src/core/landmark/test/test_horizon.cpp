// The horizon on real-looking frames: region evidence finds a hazy horizon the fixed edge
// thresholds miss, collinear pieces merge robustly, and where no sky is in view (indoors) it
// abstains.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/landmark/horizon_finder.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/sim/scene_file.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;

// The lines the Hough found (without the horizon's own segment, which has no votes).
std::vector<DetectedLine> houghLines(const std::vector<DetectedLine>& lines) {
  std::vector<DetectedLine> out;
  for (const DetectedLine& l : lines) {
    if (l.votes > 0) out.push_back(l);
  }
  return out;
}

// A hazy horizon: a smooth sky brightening towards the top, and a textured ground that fades
// into haze near the horizon, which is a soft step of 30 grey levels (edge values about 32,
// under the fixed gray threshold of 60). The horizon line is y = row + slope x.
cv::Mat hazyFrame(double row, double slope) {
  cv::Mat image(480, 640, CV_8UC3);
  cv::Mat texture(480, 640, CV_32F);
  cv::RNG rng(7);
  rng.fill(texture, cv::RNG::NORMAL, 0.0, 40.0);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const double d = y - (row + slope * x);             // below the horizon: d > 0
      const double ground = 0.5 * (1 + std::tanh(d / 2.5));  // the soft step
      const double haze = std::exp(-std::max(0.0, d) / 120);  // texture grows away from it
      const double sky_b = 225 + 15 * (1 - y / 480.0), sky_g = 200 + 10 * (1 - y / 480.0), sky_r = 180;
      const double t = ground * (1 - haze) * texture.at<float>(y, x);
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uint8_t>(sky_b - ground * 30 + t),
                                            cv::saturate_cast<uint8_t>(sky_g - ground * 18 + t),
                                            cv::saturate_cast<uint8_t>(sky_r - ground * 12 + t));
    }
  }
  return image;
}

TEST(Horizon, HazyHorizonFoundWhereFixedThresholdsMissIt) {
  const double row = 190, slope = std::tan(6 * kDeg);
  const cv::Mat image = hazyFrame(row, slope);
  LandmarkDetector detector;
  LandmarkResult result;
  detector.detectInImage(image, LandmarkOptions(), &result);
  // The fixed edge classes leave the soft step out of the edge objects: from the lines alone
  // there is no horizon.
  EXPECT_FALSE(findHorizon(houghLines(result.lines), image.cols, image.rows, HorizonOptions()).found);
  // The region evidence and the frame's own edge statistics find it.
  const HorizonEstimate& h = result.horizon;
  ASSERT_TRUE(h.found) << "confidence " << h.confidence << " (separation " << h.separation << ", sky brighter "
                       << h.sky_brighter << ", ground rougher " << h.ground_rougher << ", textured "
                       << h.ground_textured << ")";
  const ImageLine truth = lineThroughPoints(0, row, 1, row + slope);
  EXPECT_LT(lineAngleDifference(h.line.theta, truth.theta), 0.5 * kDeg);
  EXPECT_LT(std::fabs(signedDistance(truth, 320, 0.5 * (h.y1 + h.y2) + slope * (320 - 0.5 * (h.x1 + h.x2)))), 3.0);
  EXPECT_GT(h.confidence, 0.5);
  // ... and its supported segment is among the lines.
  bool on_it = false;
  for (const DetectedLine& l : result.lines) {
    on_it = on_it || (lineAngleDifference(l.line.theta, truth.theta) < 1 * kDeg && l.length > 300 &&
                      std::fabs(signedDistance(truth, 0.5 * (l.x1 + l.x2), 0.5 * (l.y1 + l.y2))) < 3);
  }
  EXPECT_TRUE(on_it);
  // With adaptive edge classes (the gray band at 6 x the local median edge value where the image
  // is smooth), the Hough finds the soft step too.
  LandmarkOptions adaptive;
  adaptive.objects.adaptive = true;
  LandmarkResult adapted;
  detector.detectInImage(image, adaptive, &adapted);
  const HorizonEstimate from_lines = findHorizon(houghLines(adapted.lines), image.cols, image.rows, HorizonOptions());
  ASSERT_TRUE(from_lines.found);
  EXPECT_LT(lineAngleDifference(from_lines.line.theta, truth.theta), 0.5 * kDeg);
  std::printf("[ hazy horizon ] confidence %.2f (separation %.2f, sky brighter %.2f, ground rougher %.2f, textured %.2f)\n",
              h.confidence, h.separation, h.sky_brighter, h.ground_rougher, h.ground_textured);
}

// A level piece of horizon along y = y0 from x0 to x1, with its pixels.
DetectedLine piece(double x0, double x1, double y0) {
  DetectedLine l;
  l.line = lineThroughPoints(x0, y0, x1, y0);
  l.x1 = x0;
  l.x2 = x1;
  l.y1 = l.y2 = y0;
  l.length = x1 - x0;
  for (double x = x0; x <= x1; x += 1) l.sums.addPixel(x, y0);
  return l;
}

TEST(Horizon, AnOutlierPieceDoesNotTiltTheMergedLine) {
  // Three pieces of a level horizon; a fourth parallel piece 3.9 px off joins through the third
  // (its ends lie within the 4-px merge distance of it), and a fifth 7.8 px off through the
  // fourth. The fifth lies far from the merged line: it is dropped, not fitted.
  std::vector<DetectedLine> lines = {piece(0, 190, 100), piece(200, 390, 100), piece(400, 500, 100),
                                     piece(510, 570, 103.9), piece(580, 639, 107.8)};
  const HorizonOptions options;
  const HorizonEstimate h = findHorizon(lines, 640, 480, options);
  ASSERT_TRUE(h.found);
  EXPECT_EQ(h.pieces, 4);
  PointSums kept;
  for (int i = 0; i < 4; ++i) kept.add(lines[i].sums);
  ImageLine expected;
  ASSERT_TRUE(kept.fitLine(&expected));
  EXPECT_NEAR(h.line.theta, expected.theta, 1e-9);
  EXPECT_NEAR(h.line.intercept, expected.intercept, 1e-6);
  // All five fitted together tilt by more.
  PointSums all = kept;
  all.add(lines[4].sums);
  ImageLine tilted;
  ASSERT_TRUE(all.fitLine(&tilted));
  EXPECT_GT(std::fabs(tilted.theta), std::fabs(h.line.theta) + 0.05 * kDeg);
}

TEST(Horizon, AbstainsIndoorsWhereNoSkyIsInView) {
  // A carpet with white field lines, the camera pitched down: long straight lines across the
  // image, but neither side looks like sky above ground.
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_indoor.yaml")));
  LandmarkDetector detector;
  LandmarkResult result;
  double worst = 0;
  size_t lines = 0;
  for (int frame = 0; frame < 60; frame += 3) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    ASSERT_FALSE(f.horizon_visible);
    detector.detectInImage(f.image, LandmarkOptions(), &result);
    EXPECT_FALSE(result.horizon.found) << "frame " << frame << ", confidence " << result.horizon.confidence;
    worst = std::max(worst, result.horizon.confidence);
    lines += result.lines.size();
  }
  EXPECT_LT(worst, 0.5);
  EXPECT_GT(lines, 20u * 10);  // the field lines are found
  std::printf("[ indoors ] no horizon in 20 frames (highest confidence %.2f), %.1f lines per frame\n", worst,
              lines / 20.0);
}

TEST(Horizon, FoundOnTheSimulatedSkyWithItsEvidence) {
  // The default scene: a smooth bright sky above textured ground, the horizon in view.
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_default.yaml")));
  LandmarkDetector detector;
  LandmarkResult result;
  const SimFrame f = simulator.render(0, 0);
  detector.detectInImage(f.image, LandmarkOptions(), &result);
  const HorizonEstimate& h = result.horizon;
  ASSERT_TRUE(h.found);
  EXPECT_GT(h.separation, 0.9);
  EXPECT_GT(h.sky_brighter, 0.9);
  EXPECT_GT(h.ground_rougher, 0.6);
  EXPECT_GT(h.ground_textured, 0.6);
  EXPECT_NEAR(h.confidence, h.separation * h.sky_brighter * h.ground_rougher * h.ground_textured, 1e-9);
  EXPECT_LT(lineAngleDifference(h.line.theta, f.horizon.theta), 0.05 * kDeg);
  // Without its colour image the same frame's edges give lines but no horizon (not weighed)...
  const cv::Mat edges = detector.edges().clone();
  detector.detect(cv::Mat(), edges, LandmarkOptions(), &result);
  EXPECT_FALSE(result.horizon.found);
  EXPECT_GT(result.lines.size(), 10u);
  // ... and the lines alone (detectInEdges, as the paper) give it.
  detector.detectInEdges(edges, LandmarkOptions(), &result);
  EXPECT_TRUE(result.horizon.found);
  // Frames too small for the region grids (under 4 cells a side) have no horizon, and no crash.
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(3, 1000), cv::Size(1000, 3), cv::Size(8, 8)}) {
    detector.detectInImage(cv::Mat(size, CV_8UC3, cv::Scalar(200, 200, 200)), LandmarkOptions(), &result);
    EXPECT_FALSE(result.horizon.found) << size;
  }
}

// A bright, faintly textured sky (clouds) over a darker ground with more texture, the horizon
// level at `row`; both textures the same smoothed noise field, scaled.
cv::Mat cloudyFrame(int row) {
  cv::Mat texture(480, 640, CV_32F);
  cv::RNG rng(11);
  rng.fill(texture, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.5);
  cv::Mat image(480, 640, CV_8UC3);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const bool sky = y < row;
      const double v = (sky ? 200 : 80) + (sky ? 12 : 20) * texture.at<float>(y, x);
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uint8_t>(v + (sky ? 20 : -10)), cv::saturate_cast<uint8_t>(v),
                                            cv::saturate_cast<uint8_t>(v - (sky ? 10 : -5)));
    }
  }
  return image;
}

// The candidate nearest the level line y = row.
HorizonEstimate candidateAt(const cv::Mat& image, int row) {
  LandmarkDetector detector;
  LandmarkResult result;
  const LandmarkOptions options;
  detector.detectInImage(image, options, &result);
  HorizonDetector horizons;
  const ImageLine truth = lineThroughPoints(0, row, 1, row);
  HorizonEstimate nearest;
  double best = INFINITY;
  for (const HorizonEstimate& c :
       horizons.candidates(image, detector.edges(), options.edge_gain, result.lines, options.horizon)) {
    const double d = std::fabs(signedDistance(c.line, 320, row)) + 100 * lineAngleDifference(c.line.theta, truth.theta);
    if (d < best) best = d, nearest = c;
  }
  return nearest;
}

TEST(Horizon, TextureEvidenceHoldsUnderAToneCurve) {
  // A tone curve (gamma 2: v -> 255 (v / 255)^2) squeezes the dark ground's steps and stretches
  // the bright sky's: in grey levels the sky becomes the rougher side. Judged on contrast
  // relative to the brightness around, the ground stays rougher and textured.
  const int row = 200;
  const cv::Mat image = cloudyFrame(row);
  cv::Mat lut(1, 256, CV_8U);
  for (int v = 0; v < 256; ++v) lut.at<uint8_t>(v) = cv::saturate_cast<uint8_t>(255 * std::pow(v / 255.0, 2));
  cv::Mat dark;
  cv::LUT(image, lut, dark);
  const HorizonEstimate before = candidateAt(image, row), after = candidateAt(dark, row);
  for (const HorizonEstimate* h : {&before, &after}) {
    EXPECT_LT(std::fabs(signedDistance(h->line, 320, row)), 2.0);
    EXPECT_GT(h->ground_rougher, 0.6) << (h == &before ? "as taken" : "gamma 2");
  }
  // The relative share of textured ground barely moves, where the share above the noise floor
  // in grey levels falls.
  const double relative_before = std::exp(before.features[kGroundTexturedRelative]);
  const double relative_after = std::exp(after.features[kGroundTexturedRelative]);
  EXPECT_GT(relative_after, 0.8 * relative_before);
  EXPECT_LT(after.ground_textured, before.ground_textured);
  std::printf("[ tone curve ] ground rougher %.2f -> %.2f; textured %.2f -> %.2f, relative %.2f -> %.2f\n",
              before.ground_rougher, after.ground_rougher, before.ground_textured, after.ground_textured,
              relative_before, relative_after);
}

TEST(Horizon, NeverSteeperThanTheLimit) {
  // The hazy horizon rolled 20 degrees: found there when the limit allows it; with a 10-degree
  // limit the searched splits stop at 10 degrees and the fit must not turn past it either.
  const double row = 70, slope = std::tan(20 * kDeg);
  const cv::Mat image = hazyFrame(row, slope);
  LandmarkDetector detector;
  LandmarkResult result;
  LandmarkOptions options;
  options.horizon.max_angle_deg = 30;
  detector.detectInImage(image, options, &result);
  ASSERT_TRUE(result.horizon.found);
  const ImageLine truth = lineThroughPoints(0, row, 1, row + slope);
  EXPECT_LT(lineAngleDifference(result.horizon.line.theta, truth.theta), 0.5 * kDeg);
  options.horizon.max_angle_deg = 10;
  detector.detectInImage(image, options, &result);
  EXPECT_LE(std::fabs(result.horizon.line.theta), 10 * kDeg + 1e-9);
  EXPECT_FALSE(result.horizon.found && lineAngleDifference(result.horizon.line.theta, truth.theta) < 5 * kDeg);
}

}  // namespace
}  // namespace rle_vision
