// Colour ranges from landmarks: the paper's statistics, regions from lines, the update gates,
// and the closed loop on the drifting-light scene.
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_convert.h"
#include "rle_vision/learning/color_learning.h"
#include "rle_vision/learning/color_learning_loop.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/segment/segmenter.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

std::vector<Channels> gaussianPixels(int n, double mean, double sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> d(mean, sigma);
  std::vector<Channels> out;
  for (int i = 0; i < n; ++i) {
    out.push_back(Channels{{saturateToByte(static_cast<int>(std::lround(d(rng)))), saturateToByte(static_cast<int>(std::lround(d(rng)))),
                            saturateToByte(static_cast<int>(std::lround(d(rng))))}});
  }
  return out;
}

TEST(ColorStats, LargeObjectsGetMeanPlusMinusThreeSigma) {
  ColorStats s;
  ASSERT_TRUE(colorStats(gaussianPixels(5000, 100, 5, 1), &s));
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(s.mean[ch], 100, 0.3);
    EXPECT_NEAR(s.sigma[ch], 5, 0.2);
    EXPECT_NEAR(s.lo[ch], 85, 1.0);
    EXPECT_NEAR(s.hi[ch], 115, 1.0);
  }
  EXPECT_EQ(s.pixels, 5000u);
}

TEST(ColorStats, SmallObjectsGetMeanPlusMinusFifteen) {
  ColorStats s;
  ASSERT_TRUE(colorStats(gaussianPixels(80, 150, 2, 2), &s));  // 80 <= 100 pixels
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(s.lo[ch], s.mean[ch] - 15, 1.0);
    EXPECT_NEAR(s.hi[ch], s.mean[ch] + 15, 1.0);
  }
}

TEST(ColorStats, OutliersMoreThanFortyFromTheMeanAreDropped) {
  std::vector<Channels> pixels = gaussianPixels(900, 100, 3, 3);
  for (int i = 0; i < 100; ++i) pixels.push_back(Channels{{250, 250, 250}});  // 10% edge pixels
  ColorStats s;
  ASSERT_TRUE(colorStats(pixels, &s));
  EXPECT_EQ(s.pixels, 900u);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(s.mean[ch], 100, 0.5);
    EXPECT_LT(s.hi[ch], 115);
  }
  EXPECT_FALSE(colorStats({}, &s));
}

DetectedLine segment(double x1, double y1, double x2, double y2, int object = 0) {
  DetectedLine l;
  l.line = lineThroughPoints(x1, y1, x2, y2);
  l.x1 = x1;
  l.y1 = y1;
  l.x2 = x2;
  l.y2 = y2;
  l.length = std::hypot(x2 - x1, y2 - y1);
  l.object = object;
  return l;
}

TEST(RegionFromLines, ClosedSquare) {
  const DetectedLine a = segment(10, 10, 50, 10), b = segment(50, 10, 50, 50), c = segment(50, 50, 10, 50),
                     d = segment(10, 50, 10, 10);
  const std::vector<cv::Point2d> region = regionFromLines({&a, &b, &c, &d});
  ASSERT_EQ(region.size(), 4u);
  std::vector<cv::Point2f> f(region.begin(), region.end());
  EXPECT_NEAR(cv::contourArea(f), 1600, 1e-6);
}

TEST(RegionFromLines, CornersWhereLinesFallShortCloseTheRegion) {
  // Three sides of a box whose segments stop 6 px short of the corners: their meeting points
  // complete the outline.
  const DetectedLine top = segment(16, 10, 44, 10), right = segment(50, 16, 50, 44), left = segment(10, 16, 10, 44);
  const std::vector<cv::Point2d> region = regionFromLines({&top, &right, &left});
  std::vector<cv::Point2f> f(region.begin(), region.end());
  // Hull of the segments plus the two top corners (10,10) and (50,10).
  EXPECT_NEAR(cv::contourArea(f), 40.0 * 34.0, 1e-6);  // (10,10)-(50,10)-(50,44)-(10,44)
  bool has_corner = false;
  for (const cv::Point2d& p : region) has_corner = has_corner || (std::fabs(p.x - 10) < 1e-6 && std::fabs(p.y - 10) < 1e-6);
  EXPECT_TRUE(has_corner);
  EXPECT_TRUE(regionFromLines({&top}).empty());
}

TEST(ColorModes, SeparatesTwoObjectsInOneRegion) {
  std::vector<Channels> pixels = gaussianPixels(600, 80, 3, 4);
  const std::vector<Channels> other = gaussianPixels(300, 160, 3, 5);
  pixels.insert(pixels.end(), other.begin(), other.end());
  const auto modes = colorModes(pixels, 20, 50);
  ASSERT_EQ(modes.size(), 2u);
  EXPECT_EQ(modes[0].size(), 600u);  // the densest first
  EXPECT_EQ(modes[1].size(), 300u);
}

// A frame with sky above row 100, ground below, and one box (whose lines are given) filled
// with `box_bgr`.
struct SyntheticFrame {
  cv::Mat image;
  LandmarkResult landmarks;
  EdgeObjectFinder objects;
};

SyntheticFrame boxFrame(const cv::Scalar& box_bgr) {
  SyntheticFrame f;
  f.image = cv::Mat(240, 320, CV_8UC3, cv::Scalar(50, 140, 40));
  f.image(cv::Rect(0, 0, 320, 100)).setTo(cv::Scalar(235, 205, 170));
  f.image(cv::Rect(100, 140, 60, 50)).setTo(box_bgr);
  f.landmarks.lines = {segment(100, 140, 160, 140), segment(160, 140, 160, 190), segment(160, 190, 100, 190),
                       segment(100, 190, 100, 140)};
  f.landmarks.horizon.found = true;
  f.landmarks.horizon.line = lineThroughPoints(0, 99.5, 319, 99.5);
  return f;
}

std::vector<ColorClass> obstacleClasses() {
  return {test::makeClass("red", ColorSpace::YUV, {{30, 85, 184}}, {{150, 128, 255}}),
          test::makeClass("blue", ColorSpace::YUV, {{15, 163, 60}}, {{120, 235, 128}})};
}

TEST(ColorLearner, FollowsAnObjectsColour) {
  ColorLearner learner(obstacleClasses(), LearningOptions());
  const SyntheticFrame f = boxFrame(cv::Scalar(30, 30, 150));  // a darker red than configured
  ASSERT_TRUE(learner.update(f.image, f.landmarks, f.objects, 0.0));
  const ColorClass& red = learner.classes()[0];
  EXPECT_EQ(red.source, "learned");
  const Channels yuv = yuvFromRgb(150, 30, 30);
  // A fifth of the way (blend 0.2) from the configured range towards the measured one: the
  // eroded region is over 100 px of one colour, so mean +- 3 sigma = the colour itself.
  EXPECT_NEAR(red.min[0], 30 + 0.2 * (yuv[0] - 30), 1.0);
  EXPECT_NEAR(red.max[0], 150 + 0.2 * (yuv[0] - 150), 1.0);
  EXPECT_EQ(learner.classes()[1].source, "config");  // blue untouched
  ASSERT_EQ(learner.lastMeasurements().size(), 1u);  // the eroded region holds only the box
  EXPECT_EQ(learner.lastMeasurements()[0].matched_class, 0);
}

// A class with a verifier keeps the range its verifier was trained on.
TEST(ColorLearner, LeavesAClassWithAVerifierAsConfigured) {
  std::vector<ColorClass> classes = obstacleClasses();
  classes[0].verifier_file = "red_verifier.yml";
  ColorLearner learner(classes, LearningOptions());
  const SyntheticFrame f = boxFrame(cv::Scalar(30, 30, 150));  // what FollowsAnObjectsColour learns red from
  learner.update(f.image, f.landmarks, f.objects, 0.0);
  EXPECT_EQ(learner.classes()[0].source, "config");
  EXPECT_EQ(learner.classes()[0].min, classes[0].min);
  EXPECT_EQ(learner.classes()[0].max, classes[0].max);
  for (const auto& m : learner.lastMeasurements()) EXPECT_NE(m.matched_class, 0);
}

TEST(ColorLearner, AGroundColouredObjectNeverWidensAClass) {
  // A "class" that holds the ground's colour at its edge would match a ground-coloured region:
  // the region is the ground, and the update is refused.
  const Channels ground = yuvFromRgb(40, 140, 50);
  std::vector<ColorClass> classes = obstacleClasses();
  classes.push_back(test::makeClass("greenish", ColorSpace::YUV,
                                    {{static_cast<uint8_t>(ground[0] - 30), static_cast<uint8_t>(ground[1] - 2), static_cast<uint8_t>(ground[2] - 2)}},
                                    {{static_cast<uint8_t>(ground[0] + 30), static_cast<uint8_t>(ground[1] + 30), static_cast<uint8_t>(ground[2] + 30)}}));
  ColorLearner learner(classes, LearningOptions());
  SyntheticFrame f = boxFrame(cv::Scalar(50, 140, 40));  // the box is exactly ground-coloured
  for (int i = 0; i < 20; ++i) learner.update(f.image, f.landmarks, f.objects, i / 30.0);
  for (size_t k = 0; k < classes.size(); ++k) {
    EXPECT_EQ(learner.classes()[k].min, classes[k].min) << classes[k].name;
    EXPECT_EQ(learner.classes()[k].max, classes[k].max) << classes[k].name;
  }
  bool refused = false;
  for (const auto& m : learner.lastMeasurements()) refused = refused || m.rejected.find("ground") != std::string::npos;
  EXPECT_TRUE(refused);
}

// A small ball (a disc, radius 5 px, 81 px: no lines bound it) on the ground of the box frame,
// brightness `gain` of its colour, with sensor noise.
cv::Mat ballFrame(double gain, uint32_t seed) {
  cv::Mat image = boxFrame(cv::Scalar(50, 140, 40)).image;  // the box ground-coloured: no box
  cv::circle(image, cv::Point(200, 170), 5, cv::Scalar(40 * gain, 120 * gain, 240 * gain), cv::FILLED);
  cv::Mat noise(image.size(), CV_16SC3);
  cv::theRNG().state = seed;
  cv::randn(noise, 0, 2);
  cv::Mat sum;
  image.convertTo(sum, CV_16SC3);
  sum += noise;
  sum.convertTo(image, CV_8UC3);
  return image;
}

// The ball's class, measured on the first frame as rle_vision_calibrate would (mean +- 15).
ColorClass ballClass() {
  const Channels yuv = yuvFromRgb(240, 120, 40);
  Channels lo, hi;
  for (int ch = 0; ch < 3; ++ch) lo[ch] = saturateToByte(yuv[ch] - 15), hi[ch] = saturateToByte(yuv[ch] + 15);
  return test::makeClass("ball", ColorSpace::YUV, lo, hi, 20);
}

// Whether the class finds the ball in the frame: a region of it near the disc's centre.
bool findsBall(const ColorClass& ball, const cv::Mat& image) {
  Segmenter segmenter;
  std::vector<Region> regions;
  segmenter.segment(image, PixelFormat::BGR8, ColorTable({ball}), &regions);
  return std::any_of(regions.begin(), regions.end(), [](const Region& r) { return std::hypot(r.cx - 200, r.cy - 170) < 3; });
}

TEST(ColorLearner, BlobsLetASmallObjectFollowTheLight) {
  // The ball dims to 55% over 60 frames; no lines bound it, so only its blob can teach.
  for (const bool from_blobs : {false, true}) {
    LearningOptions options;
    options.from_blobs = from_blobs;
    ColorLearner learner({ballClass()}, options);
    LandmarkDetector detector;
    LandmarkResult landmarks;
    int found = 0;
    for (int i = 0; i <= 60; ++i) {
      const cv::Mat image = ballFrame(1.0 - 0.45 * i / 60.0, 100 + i);
      found += findsBall(learner.classes()[0], image);
      detector.detectInImage(image, LandmarkOptions(), &landmarks);
      learner.update(image, landmarks, detector.edgeObjects(), i / 30.0);
    }
    std::printf("[ small ball ] learning from blobs %s: found in %d of 61 frames\n", from_blobs ? "on " : "off", found);
    if (from_blobs) {
      EXPECT_GE(found, 58);
      EXPECT_EQ(learner.classes()[0].source, "learned");
    } else {
      EXPECT_LT(found, 45);
      EXPECT_EQ(learner.classes()[0].source, "config");
    }
  }
}

cv::Scalar bgrOfYuv(int y, int u, int v) {
  cv::Mat yuv(1, 1, CV_8UC3, cv::Scalar(y, u, v)), bgr;
  cv::cvtColor(yuv, bgr, cv::COLOR_YUV2BGR);
  return cv::Scalar(bgr.at<cv::Vec3b>(0, 0));
}

TEST(ColorLearner, BlobMeasurementsReachingTheGroundAreRefused) {
  // A ball class just above the ground's brightness; the ball's core is in it, its rim nearly
  // ground-coloured (within the ring margin): the measurement with the rim spans the ground's
  // colour, so it is refused as background and the class stays off the ground.
  const Channels g = yuvFromRgb(40, 140, 50);
  const ColorClass ball = test::makeClass("ball", ColorSpace::YUV, {{static_cast<uint8_t>(g[0] + 14), g[1], g[2]}},
                                          {{static_cast<uint8_t>(g[0] + 40), static_cast<uint8_t>(g[1] + 20),
                                            static_cast<uint8_t>(g[2] + 20)}}, 20);
  LearningOptions options;
  options.from_blobs = true;
  ColorLearner learner({ball}, options);
  SyntheticFrame f = boxFrame(cv::Scalar(50, 140, 40));  // the box ground-coloured: no box
  f.landmarks.lines.clear();
  cv::circle(f.image, cv::Point(200, 170), 9, bgrOfYuv(g[0] + 4, g[1] + 2, g[2] + 2), cv::FILLED);  // the rim
  cv::circle(f.image, cv::Point(200, 170), 6, bgrOfYuv(g[0] + 26, g[1] + 8, g[2] + 8), cv::FILLED);  // the core
  for (int i = 0; i < 20; ++i) learner.update(f.image, f.landmarks, f.objects, i / 30.0);
  const ColorStats* ground = learner.groundStats(ColorSpace::YUV);
  ASSERT_NE(ground, nullptr);
  const ColorClass& c = learner.classes()[0];
  bool overlaps_ground = true;
  for (int ch = 0; ch < 3; ++ch) overlaps_ground = overlaps_ground && !(c.max[ch] < ground->lo[ch] || ground->hi[ch] < c.min[ch]);
  EXPECT_FALSE(overlaps_ground);
  EXPECT_EQ(c.min, ball.min);
  EXPECT_EQ(c.max, ball.max);
  bool refused = false, measured = false;
  for (const auto& m : learner.lastMeasurements()) {
    if (!m.from_blob || !m.pixels_box.contains(cv::Point(200, 170))) continue;
    measured = true;
    refused = m.rejection == ColorLearner::Rejection::kBackground;
  }
  EXPECT_TRUE(measured) << "the ball's blob must have been measured";
  EXPECT_TRUE(refused);
  // Without the rim the same class measures the ball and applies it: the gate, not the blob
  // path, refused.
  ColorLearner clean({ball}, options);
  SyntheticFrame plain = boxFrame(cv::Scalar(50, 140, 40));
  plain.landmarks.lines.clear();
  cv::circle(plain.image, cv::Point(200, 170), 6, bgrOfYuv(g[0] + 26, g[1] + 8, g[2] + 8), cv::FILLED);
  clean.update(plain.image, plain.landmarks, plain.objects, 0.0);
  bool applied = false;
  for (const auto& m : clean.lastMeasurements()) {
    applied = applied || (m.from_blob && m.pixels_box.contains(cv::Point(200, 170)) && m.matched_class == 0 &&
                          m.rejection == ColorLearner::Rejection::kNone);
  }
  EXPECT_TRUE(applied);
}

TEST(ColorLearner, ARegionTheClassDoesNotHoldLeavesItAlone) {
  // A box bounded by lines whose colour lies just past a class's range on one channel (a white
  // line beside a cream ball's range): near the class's centre, but the class holds none of
  // it, so it does not pull the range over itself. The same box inside the range teaches it.
  const cv::Scalar box_bgr(60, 200, 200);
  const Channels c = yuvFromRgb(200, 200, 60);
  auto classWithUUpTo = [&](int u_hi) {
    return test::makeClass("cream", ColorSpace::YUV,
                           {{static_cast<uint8_t>(c[0] - 30), static_cast<uint8_t>(u_hi - 40), static_cast<uint8_t>(c[2] - 20)}},
                           {{static_cast<uint8_t>(c[0] + 30), static_cast<uint8_t>(u_hi), static_cast<uint8_t>(c[2] + 20)}});
  };
  const ColorClass beside = classWithUUpTo(c[1] - 8), holding = classWithUUpTo(c[1] + 8);
  const SyntheticFrame f = boxFrame(box_bgr);
  ColorLearner learner({beside}, LearningOptions());
  for (int i = 0; i < 20; ++i) learner.update(f.image, f.landmarks, f.objects, i / 30.0);
  EXPECT_EQ(learner.classes()[0].min, beside.min);
  EXPECT_EQ(learner.classes()[0].max, beside.max);
  ASSERT_EQ(learner.lastMeasurements().size(), 1u);
  EXPECT_EQ(learner.lastMeasurements()[0].rejection, ColorLearner::Rejection::kNotInRange);
  ColorLearner follows({holding}, LearningOptions());
  EXPECT_TRUE(follows.update(f.image, f.landmarks, f.objects, 0.0));
  EXPECT_EQ(follows.classes()[0].source, "learned");
}

TEST(ColorLearner, BlobLearningNeverTakesInTheBackground) {
  // A ball whose rim is a little past its class's U range: measured with its ring, the class
  // moves towards the rim's colour. Where a patch of the rim's colour lies elsewhere in the
  // frame (a wall with no lines, not the ground's colour), the move that would take the patch
  // in is refused; without the patch the class takes the rim's colour in.
  const ColorClass ball = test::makeClass("ball", ColorSpace::YUV, {{165, 88, 135}}, {{195, 112, 165}}, 20);
  const cv::Scalar rim_bgr = bgrOfYuv(180, 115, 150);
  const Channels rim = yuvFromRgb(static_cast<int>(rim_bgr[2]), static_cast<int>(rim_bgr[1]), static_cast<int>(rim_bgr[0]));
  ASSERT_GT(rim[1], ball.max[1]);
  LearningOptions options;
  options.from_blobs = true;
  auto frame = [&](bool patch) {
    SyntheticFrame f = boxFrame(cv::Scalar(50, 140, 40));  // the box ground-coloured: no box
    f.landmarks.lines.clear();
    cv::circle(f.image, cv::Point(200, 170), 6, rim_bgr, cv::FILLED);                   // the rim
    cv::circle(f.image, cv::Point(200, 170), 4, bgrOfYuv(180, 100, 150), cv::FILLED);  // the core
    if (patch) f.image(cv::Rect(20, 120, 50, 50)).setTo(rim_bgr);
    return f;
  };
  const SyntheticFrame with_patch = frame(true), without = frame(false);
  ColorLearner learner({ball}, options), clean({ball}, options);
  bool refused = false;
  for (int i = 0; i < 20; ++i) {
    learner.update(with_patch.image, with_patch.landmarks, with_patch.objects, i / 30.0);
    for (const auto& m : learner.lastMeasurements()) {
      refused = refused || (m.from_blob && m.rejection == ColorLearner::Rejection::kTakesInBackground);
    }
    clean.update(without.image, without.landmarks, without.objects, i / 30.0);
  }
  EXPECT_TRUE(refused);
  EXPECT_LT(learner.classes()[0].max[1], rim[1]) << "the class took the patch in";
  EXPECT_GE(clean.classes()[0].max[1], rim[1]);
}

TEST(ColorLearner, RegionsAtTheHorizonAreNotObstacles) {
  ColorLearner learner(obstacleClasses(), LearningOptions());
  SyntheticFrame f = boxFrame(cv::Scalar(30, 30, 150));
  f.landmarks.horizon.line = lineThroughPoints(0, 150, 319, 150);  // through the box
  EXPECT_FALSE(learner.update(f.image, f.landmarks, f.objects, 0.0));
  EXPECT_EQ(learner.classes()[0].source, "config");
}

TEST(ColorLearner, NoClassGrowsIntoAnother) {
  // Two classes split on V only: "near" holds the box's colour, "far" starts just above. The
  // noisy box's measured range reaches into "far"; the update that would overlap is refused.
  const Channels c = yuvFromRgb(210, 40, 40);
  const uint8_t y_lo = static_cast<uint8_t>(c[0] - 40), y_hi = static_cast<uint8_t>(c[0] + 40);
  const uint8_t u_lo = static_cast<uint8_t>(c[1] - 30), u_hi = static_cast<uint8_t>(c[1] + 30);
  const std::vector<ColorClass> classes = {
      test::makeClass("near", ColorSpace::YUV, {{y_lo, u_lo, static_cast<uint8_t>(c[2] - 25)}}, {{y_hi, u_hi, static_cast<uint8_t>(c[2] + 2)}}),
      test::makeClass("far", ColorSpace::YUV, {{y_lo, u_lo, static_cast<uint8_t>(c[2] + 12)}}, {{y_hi, u_hi, 255}})};
  ColorLearner learner(classes, LearningOptions());
  SyntheticFrame f = boxFrame(cv::Scalar(40, 40, 210));
  cv::Mat noise(50, 60, CV_16SC3), box;
  cv::RNG(7).fill(noise, cv::RNG::NORMAL, 0, 8);
  f.image(cv::Rect(100, 140, 60, 50)).convertTo(box, CV_16SC3);
  box += noise;
  box.convertTo(f.image(cv::Rect(100, 140, 60, 50)), CV_8UC3);
  bool refused = false;
  for (int i = 0; i < 30; ++i) {
    learner.update(f.image, f.landmarks, f.objects, i / 30.0);
    const ColorClass &near = learner.classes()[0], &far = learner.classes()[1];
    ASSERT_LT(near.max[2], far.min[2]) << "frame " << i;
    for (const auto& m : learner.lastMeasurements()) refused = refused || m.rejected.find("overlap class 'far'") != std::string::npos;
  }
  EXPECT_TRUE(refused) << "the test should have driven 'near' against 'far'";
}

TEST(ColorLearner, UnmeasuredClassesDriftBackToTheirConfiguredRange) {
  LearningOptions options;
  options.stale_after_s = 1.0;
  ColorLearner learner(obstacleClasses(), options);
  const SyntheticFrame seen = boxFrame(cv::Scalar(30, 30, 150));
  for (int i = 0; i < 10; ++i) learner.update(seen.image, seen.landmarks, seen.objects, i / 30.0);
  EXPECT_EQ(learner.classes()[0].source, "learned");
  SyntheticFrame empty = boxFrame(cv::Scalar(50, 140, 40));
  empty.landmarks.lines.clear();
  for (int i = 0; i < 120; ++i) learner.update(empty.image, empty.landmarks, empty.objects, 1.0 + i / 30.0);
  EXPECT_EQ(learner.classes()[0].min, obstacleClasses()[0].min);
  EXPECT_EQ(learner.classes()[0].max, obstacleClasses()[0].max);
  EXPECT_EQ(learner.classes()[0].source, "config");
}

TEST(ColorLearner, ResumesFromRangesLearnedBefore) {
  // A restarted landmark node continues from the ranges the tracker still uses: same name and
  // space and source "learned" resume; anything else is ignored.
  ColorLearner learner(obstacleClasses(), LearningOptions());
  std::vector<ColorClass> earlier = obstacleClasses();
  earlier[0].min = {{20, 90, 170}};
  earlier[0].max = {{120, 125, 240}};
  earlier[0].source = "learned";
  earlier[1].min = {{0, 0, 0}};  // blue: configured, not learned
  ColorClass other = test::makeClass("green", ColorSpace::YUV, {{0, 0, 0}}, {{255, 255, 255}});
  other.source = "learned";
  earlier.push_back(other);
  ColorClass wrong_space = test::makeClass("blue", ColorSpace::RGB, {{0, 0, 0}}, {{9, 9, 9}});
  wrong_space.source = "learned";
  earlier.push_back(wrong_space);
  EXPECT_EQ(learner.resume(earlier, 5.0), 1);
  ASSERT_EQ(learner.classes().size(), 2u);
  EXPECT_EQ(learner.classes()[0].min, earlier[0].min);
  EXPECT_EQ(learner.classes()[0].max, earlier[0].max);
  EXPECT_EQ(learner.classes()[0].source, "learned");
  EXPECT_EQ(learner.classes()[1].min, obstacleClasses()[1].min);
  EXPECT_EQ(learner.classes()[1].source, "config");
  // Resumed ranges are ordinary learned state: unseen, they drift back to the configured range.
  LearningOptions options;
  options.stale_after_s = 1.0;
  learner.setOptions(options);
  SyntheticFrame empty = boxFrame(cv::Scalar(50, 140, 40));
  empty.landmarks.lines.clear();
  for (int i = 0; i < 120; ++i) learner.update(empty.image, empty.landmarks, empty.objects, 5.0 + i / 30.0);
  EXPECT_EQ(learner.classes()[0].min, obstacleClasses()[0].min);
  EXPECT_EQ(learner.classes()[0].source, "config");
}

// The Landmark node's loop: changed ranges go out at once, then at most once per publish
// period (the changes in between are not lost); switching learning off hands the configured
// ranges back once; a restarted node resumes from the tracker's learned ranges.
TEST(ColorLearningLoop, PublishesChangesAtMostOncePerPeriod) {
  ColorLearningLoop loop(obstacleClasses());
  const SyntheticFrame f = boxFrame(cv::Scalar(30, 30, 150));
  const LearningOptions options;
  ColorLearningLoop::Step step = loop.learn(f.image, f.landmarks, f.objects, 0.0, 100.0, options, 0.5);
  ASSERT_TRUE(step.publish);
  EXPECT_EQ(step.classes[0].source, "learned");
  const Channels first_min = step.classes[0].min;
  // The range keeps moving (blend 0.2 per frame) but the next message waits for the period.
  int published = 0;
  for (int i = 1; i <= 14; ++i) published += loop.learn(f.image, f.landmarks, f.objects, i / 30.0, 100.0 + i / 30.0, options, 0.5).publish;
  EXPECT_EQ(published, 0);
  step = loop.learn(f.image, f.landmarks, f.objects, 0.5, 100.5, options, 0.5);
  ASSERT_TRUE(step.publish);
  EXPECT_NE(step.classes[0].min, first_min);
  // Off: the configured set, once.
  step = loop.stop(options);
  ASSERT_TRUE(step.publish);
  EXPECT_EQ(step.classes[0].min, obstacleClasses()[0].min);
  EXPECT_EQ(step.classes[0].source, "config");
  EXPECT_FALSE(loop.stop(options).publish);
  EXPECT_EQ(loop.learner().classes()[0].min, obstacleClasses()[0].min);  // starts over when on again
}

TEST(ColorLearningLoop, ResumesOnceFromTheTrackersLearnedRanges) {
  ColorLearningLoop loop(obstacleClasses());
  std::vector<ColorClass> earlier = obstacleClasses();
  earlier[0].min = {{20, 90, 170}};
  earlier[0].source = "learned";
  loop.offerResume(earlier);
  SyntheticFrame empty = boxFrame(cv::Scalar(50, 140, 40));
  empty.landmarks.lines.clear();
  ColorLearningLoop::Step step = loop.learn(empty.image, empty.landmarks, empty.objects, 0.0, 0.0, LearningOptions(), 0.5);
  EXPECT_EQ(step.resumed, 1);
  EXPECT_EQ(loop.learner().classes()[0].min, earlier[0].min);
  // Offered again later (the latched topic once more): nothing changes any more.
  loop.offerResume(obstacleClasses());
  step = loop.learn(empty.image, empty.landmarks, empty.objects, 0.1, 0.1, LearningOptions(), 0.5);
  EXPECT_EQ(step.resumed, 0);
  EXPECT_EQ(loop.learner().classes()[0].min, earlier[0].min);
  EXPECT_EQ(validateLearningLoopOptions(LearningLoopOptions()), "");
  LearningLoopOptions nan;
  nan.publish_period_s = NAN;
  EXPECT_NE(validateLearningLoopOptions(nan), "");
}

// The floor's colour (the field stage's) goes out with the learned ranges as class "field":
// added to a set without one (sized to the view), in place of a configured one (keeping its
// look); a move of one level is a change to publish; nullptr takes it out again.
TEST(ColorLearningLoop, PublishesTheFieldColourAsAClass) {
  SyntheticFrame empty = boxFrame(cv::Scalar(50, 140, 40));
  empty.landmarks.lines.clear();  // nothing learned: only the field changes the set
  ColorClass floor = test::makeClass("anything", ColorSpace::YUV, {{60, 100, 90}}, {{140, 130, 120}});
  ColorLearningLoop loop(obstacleClasses());
  loop.setFieldColour(&floor);
  ColorLearningLoop::Step step = loop.learn(empty.image, empty.landmarks, empty.objects, 0.0, 0.0, LearningOptions(), 0.5);
  ASSERT_TRUE(step.publish);
  ASSERT_EQ(step.classes.size(), 3u);
  EXPECT_EQ(step.classes[2].name, kFieldClassName);
  EXPECT_EQ(step.classes[2].source, "learned");
  EXPECT_EQ(step.classes[2].min, floor.min);
  EXPECT_EQ(step.classes[2].min_area_px, static_cast<uint32_t>(0.005 * empty.image.total()));
  loop.setFieldColour(&floor);  // unchanged: nothing to publish
  EXPECT_FALSE(loop.learn(empty.image, empty.landmarks, empty.objects, 1.0, 1.0, LearningOptions(), 0.5).publish);
  floor.max[1] = 131;
  loop.setFieldColour(&floor);
  step = loop.learn(empty.image, empty.landmarks, empty.objects, 2.0, 2.0, LearningOptions(), 0.5);
  ASSERT_TRUE(step.publish);
  EXPECT_EQ(step.classes[2].max[1], 131);
  // Within the publish period a small move waits; one of over a third of the half width (here
  // 40 levels of Y: 13.3) does not: the tracker's copy would lose the floor's outer pixels.
  floor.min[0] = 65;
  loop.setFieldColour(&floor);
  EXPECT_FALSE(loop.learn(empty.image, empty.landmarks, empty.objects, 2.1, 2.1, LearningOptions(), 0.5).publish);
  floor.min[0] = 74;
  floor.max[0] = 154;
  loop.setFieldColour(&floor);
  step = loop.learn(empty.image, empty.landmarks, empty.objects, 2.2, 2.2, LearningOptions(), 0.5);
  ASSERT_TRUE(step.publish);
  EXPECT_EQ(step.classes[2].max[0], 154);
  loop.setFieldColour(nullptr);
  ColorLearningLoop::Step without = loop.learn(empty.image, empty.landmarks, empty.objects, 3.0, 3.0, LearningOptions(), 0.5);
  ASSERT_TRUE(without.publish);  // taken out of the tracker's set
  EXPECT_EQ(without.classes.size(), 2u);
  loop.setFieldColour(nullptr);
  EXPECT_FALSE(loop.learn(empty.image, empty.landmarks, empty.objects, 4.0, 4.0, LearningOptions(), 0.5).publish);
  // A configured field class is replaced by the followed range, keeping its look and size limit.
  std::vector<ColorClass> with_field = obstacleClasses();
  with_field.push_back(test::makeClass("field", ColorSpace::YUV, {{0, 0, 0}}, {{255, 127, 127}}));
  with_field.back().display_rgb = {{1, 2, 3}};
  with_field.back().min_area_px = 77;
  ColorLearningLoop configured(with_field);
  configured.setFieldColour(&floor);
  step = configured.learn(empty.image, empty.landmarks, empty.objects, 0.0, 0.0, LearningOptions(), 0.5);
  ASSERT_EQ(step.classes.size(), 3u);
  EXPECT_EQ(step.classes[2].min, floor.min);
  EXPECT_EQ(step.classes[2].max, floor.max);
  EXPECT_EQ(step.classes[2].display_rgb, with_field.back().display_rgb);
  EXPECT_EQ(step.classes[2].min_area_px, 77u);
  EXPECT_EQ(step.classes[2].source, "learned");
}

// A class with a verifier has a permissive range, and its verifier was trained on candidates
// the floor's colour had carved first: the field class goes in before it.
TEST(ColorLearningLoop, TheFieldClassComesBeforeAClassWithAVerifier) {
  SyntheticFrame empty = boxFrame(cv::Scalar(50, 140, 40));
  empty.landmarks.lines.clear();
  std::vector<ColorClass> classes = obstacleClasses();
  classes[1].verifier_file = "ball_verifier.yml.gz";
  const ColorClass floor = test::makeClass("anything", ColorSpace::YUV, {{60, 100, 90}}, {{140, 130, 120}});
  ColorLearningLoop loop(classes);
  loop.setFieldColour(&floor);
  const ColorLearningLoop::Step step = loop.learn(empty.image, empty.landmarks, empty.objects, 0.0, 0.0, LearningOptions(), 0.5);
  ASSERT_TRUE(step.publish);
  ASSERT_EQ(step.classes.size(), 3u);
  EXPECT_EQ(step.classes[0].name, "red");
  EXPECT_EQ(step.classes[1].name, kFieldClassName);
  EXPECT_EQ(step.classes[1].min_area_px, static_cast<uint32_t>(0.005 * empty.image.total()));
  EXPECT_EQ(step.classes[2].name, "blue");
  EXPECT_EQ(step.classes[2].verifier_file, "ball_verifier.yml.gz");
}

TEST(ColorLearner, PersistentUnknownColoursBecomeLearnedClassesWhenAsked) {
  LearningOptions options;
  options.create_classes = true;
  options.persist_frames = 5;
  const SyntheticFrame f = boxFrame(cv::Scalar(200, 200, 20));  // cyan: no class
  ColorLearner off(obstacleClasses(), LearningOptions());
  ColorLearner on(obstacleClasses(), options);
  for (int i = 0; i < 6; ++i) {
    off.update(f.image, f.landmarks, f.objects, i / 30.0);
    on.update(f.image, f.landmarks, f.objects, i / 30.0);
  }
  EXPECT_EQ(off.classes().size(), 2u);
  ASSERT_EQ(on.classes().size(), 3u);
  EXPECT_EQ(on.classes()[2].name, "learned_1");
  EXPECT_EQ(on.classes()[2].source, "learned");
  EXPECT_TRUE(on.classes()[2].contains(yuvFromRgb(20, 200, 200)));
}

// The closed loop on the drifting-light preset: tracker recall of obstacles (a blob of the
// box's class with bounding-box IoU >= 0.5) over time, with and without learning.
TEST(ColorLearner, ClosedLoopKeepsTheTrackerWorkingAsTheLightDrifts) {
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_drift.yaml")));
  const std::vector<ColorClass> configured = loadColorClasses(test::sourcePath("config/colors.yaml"));
  for (const bool learning : {false, true}) {
    ColorLearner learner(configured, LearningOptions());
    LandmarkDetector detector;
    LandmarkResult landmarks;
    Segmenter segmenter;
    std::vector<Region> regions;
    double worst = 1.0, last = 0.0;
    int false_blobs = 0;
    for (int window = 0; window < 16; ++window) {  // 2-s windows over 32 s
      int truths = 0, found = 0;
      for (int frame = window * 60; frame < (window + 1) * 60; frame += 3) {
        const double t = frame / 30.0;
        const SimFrame f = simulator.render(frame, t);
        if (learning) {
          detector.detectInImage(f.image, LandmarkOptions(), &landmarks);
          learner.update(f.image, landmarks, detector.edgeObjects(), t);
        }
        const ColorTable table(learning ? learner.classes() : configured);
        segmenter.segment(f.image, PixelFormat::BGR8, table, &regions);
        for (const BoxTruth& box : f.boxes) {
          if (box.area < 200 || box.pieces != 1 || box.touches_same_class) continue;
          ++truths;
          const cv::Rect truth(box.left, box.top, box.right - box.left + 1, box.bottom - box.top + 1);
          found += std::any_of(regions.begin(), regions.end(), [&](const Region& r) {
            const cv::Rect blob(r.left, r.top, r.right - r.left + 1, r.bottom - r.top + 1);
            const double inter = (blob & truth).area();
            return table.classes()[r.label - 1].name == box.color_class && inter / (blob.area() + truth.area() - inter) >= 0.5;
          });
        }
        // No blob may lie out on ground or sky: every blob touches some box. Mixed pixels in the
        // anti-aliased band along a box edge (2 px) may match a learned range; they count as the box.
        const int fringe_px = 2;
        for (const Region& r : regions) {
          const cv::Rect blob(r.left, r.top, r.right - r.left + 1, r.bottom - r.top + 1);
          const bool on_box = std::any_of(f.boxes.begin(), f.boxes.end(), [&](const BoxTruth& b) {
            const cv::Rect near_box(b.left - fringe_px, b.top - fringe_px, b.right - b.left + 1 + 2 * fringe_px,
                                    b.bottom - b.top + 1 + 2 * fringe_px);
            return b.area > 0 && (blob & near_box).area() > 0;
          });
          false_blobs += !on_box;
        }
      }
      const double recall = static_cast<double>(found) / truths;
      worst = std::min(worst, recall);
      last = recall;
    }
    std::printf("[ closed loop ] learning %s: worst 2-s recall %.2f, last %.2f, false blobs %d\n",
                learning ? "on " : "off", worst, last, false_blobs);
    if (learning) {
      EXPECT_GE(worst, 0.9);
      EXPECT_EQ(false_blobs, 0);
    } else {
      EXPECT_LT(last, 0.5);
    }
  }
}

}  // namespace
}  // namespace rle_vision
