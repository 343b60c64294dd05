// The candidate features' chroma is measured from the frame's own (FrameChroma): known answers
// for the frame's chroma, and one scene under two lights that tint it differently giving the
// same chroma features. The fast features equal the reference's (one OpenCV call a step) bit
// for bit.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "reference_candidate_features.h"
#include "rle_vision/verify/candidate_features.h"

namespace rle_vision {
namespace {

cv::Vec3b yuvOf(const cv::Vec3b& bgr) {
  cv::Mat pixel(1, 1, CV_8UC3, cv::Scalar(bgr[0], bgr[1], bgr[2])), yuv;
  cv::cvtColor(pixel, yuv, cv::COLOR_BGR2YUV);
  return yuv.at<cv::Vec3b>(0, 0);
}

TEST(FrameChroma, IsTheMedianChromaOfTheFrame) {
  // 70% of the frame is green, the rest orange: the median is the green's chroma.
  const cv::Vec3b green(60, 140, 70), orange(30, 120, 230);
  cv::Mat frame(400, 400, CV_8UC3, cv::Scalar(green[0], green[1], green[2]));
  frame(cv::Rect(280, 0, 120, 400)).setTo(cv::Scalar(orange[0], orange[1], orange[2]));
  const FrameChroma chroma = frameChroma(frame);
  EXPECT_EQ(chroma.u, yuvOf(green)[1]);
  EXPECT_EQ(chroma.v, yuvOf(green)[2]);
  // Mostly orange: the orange's.
  frame(cv::Rect(0, 0, 240, 400)).setTo(cv::Scalar(orange[0], orange[1], orange[2]));
  EXPECT_EQ(frameChroma(frame).u, yuvOf(orange)[1]);
  EXPECT_EQ(frameChroma(frame).v, yuvOf(orange)[2]);
  // Not a colour frame: neutral.
  EXPECT_EQ(frameChroma(cv::Mat()).u, 128);
  EXPECT_EQ(frameChroma(cv::Mat(10, 10, CV_8UC1, cv::Scalar(3))).v, 128);
}

// A field-coloured frame with a ball, drawn in YUV with its chroma shifted by (du, dv): the same
// scene under a light that tints every colour alike.
cv::Mat tintedScene(int du, int dv) {
  cv::Mat yuv(240, 320, CV_8UC3, cv::Scalar(110, 120 + du, 110 + dv));
  cv::rectangle(yuv, cv::Rect(0, 0, 320, 60), cv::Scalar(150, 135 + du, 125 + dv), cv::FILLED);  // a wall
  cv::circle(yuv, cv::Point(160, 150), 12, cv::Scalar(170, 90 + du, 150 + dv), cv::FILLED);      // the ball
  cv::Mat bgr;
  cv::cvtColor(yuv, bgr, cv::COLOR_YUV2BGR);
  return bgr;
}

Region ballRegion() {
  Region r;
  r.label = 1;
  r.area = 441;
  r.cx = 160;
  r.cy = 150;
  r.left = 148;
  r.right = 172;
  r.top = 138;
  r.bottom = 162;
  r.var_xx = r.var_yy = 36;
  return r;
}

// The features made of chroma: the box's and the ring's mean U and V, and the chroma grid.
std::vector<int> chromaFeatures() {
  std::vector<int> index = {7, 8, 13, 14};
  for (int i = 50; i < kCandidateFeatureCount; ++i) index.push_back(i);
  return index;
}

TEST(CandidateFeatures, ChromaFromTheFramesHoldsUnderAnotherLightsTint) {
  const cv::Mat plain = tintedScene(0, 0), tinted = tintedScene(14, -12);
  CandidateFeatures a, b, b_absolute;
  candidateFeatures(plain, frameChroma(plain), ballRegion(), &a);
  candidateFeatures(tinted, frameChroma(tinted), ballRegion(), &b);
  candidateFeatures(tinted, frameChroma(plain), ballRegion(), &b_absolute);  // as if measured absolutely
  for (int i : chromaFeatures()) {
    // The BGR round trip rounds each channel: a level or two.
    EXPECT_NEAR(a[i], b[i], 2.5 / 255) << "feature " << i;
    EXPECT_GT(std::fabs(a[i] - b_absolute[i]), 9.0 / 255) << "feature " << i;
  }
  // The box minus the ring is the same with or without the frame's chroma.
  for (int i = 15; i < 18; ++i) EXPECT_FLOAT_EQ(b[i], b_absolute[i]) << "feature " << i;
  // Brightness is not chroma: the box's Y is measured as it is.
  EXPECT_NEAR(a[6], b[6], 2.5 / 255);
}

// A scene with what the features meet: flat patches (zero gradients), steps and diagonal ramps
// (gradients on the orientation bins' edges: equal |gx| and |gy|), and noise.
cv::Mat mixedScene(cv::RNG* rng) {
  cv::Mat bgr(240, 320, CV_8UC3);
  rng->fill(bgr, cv::RNG::UNIFORM, 0, 256);
  for (int i = 0; i < 12; ++i) {
    const cv::Rect r(rng->uniform(-20, 300), rng->uniform(-20, 220), rng->uniform(4, 80), rng->uniform(4, 80));
    cv::rectangle(bgr, r, cv::Scalar(rng->uniform(0, 256), rng->uniform(0, 256), rng->uniform(0, 256)), cv::FILLED);
  }
  for (int y = 100; y < 180; ++y) {
    for (int x = 200; x < 280; ++x) bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(x + y - 300, 2 * (x - y), 128);
  }
  return bgr;
}

TEST(CandidateFeatures, EqualTheReferenceBitForBit) {
  cv::RNG rng(20261207);
  CandidateFeatures fast, slow;
  cv::Mat patch_bgr, patch_yuv;
  int compared = 0;
  for (int scene = 0; scene < 6; ++scene) {
    const cv::Mat bgr = mixedScene(&rng);
    const FrameChroma chroma = frameChroma(bgr);
    for (int i = 0; i < 80; ++i) {
      Region r;
      r.left = rng.uniform(0, bgr.cols - 1), r.top = rng.uniform(0, bgr.rows - 1);
      r.right = std::min(bgr.cols - 1, r.left + rng.uniform(0, 90)), r.bottom = std::min(bgr.rows - 1, r.top + rng.uniform(0, 90));
      r.area = static_cast<uint32_t>(rng.uniform(1, (r.right - r.left + 1) * (r.bottom - r.top + 1) + 1));
      r.cx = 0.5 * (r.left + r.right), r.cy = 0.5 * (r.top + r.bottom);
      r.var_xx = rng.uniform(0.0, 300.0), r.var_yy = rng.uniform(0.0, 300.0), r.var_xy = rng.uniform(-50.0, 50.0);
      candidateFeatures(bgr, chroma, r, &fast, &patch_bgr, &patch_yuv);
      reference::candidateFeatures(bgr, chroma, r, &slow);
      for (int k = 0; k < kCandidateFeatureCount; ++k) {
        ASSERT_EQ(fast[k], slow[k]) << "feature " << k << ", scene " << scene << ", box " << r.left << "," << r.top
                                    << " to " << r.right << "," << r.bottom;
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 480);
}

TEST(CandidateFeatures, ARegionOffTheFrameOrAGreyFrameIsRefused) {
  cv::RNG rng(7);
  const cv::Mat bgr = mixedScene(&rng);
  Region inside = ballRegion(), off = ballRegion();
  off.left += 1000, off.right += 1000;
  CandidateFeatures x;
  EXPECT_NO_THROW(candidateFeatures(bgr, frameChroma(bgr), inside, &x));
  EXPECT_THROW(candidateFeatures(bgr, frameChroma(bgr), off, &x), std::invalid_argument);
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  EXPECT_THROW(candidateFeatures(grey, FrameChroma(), inside, &x), std::invalid_argument);
}

}  // namespace
}  // namespace rle_vision
