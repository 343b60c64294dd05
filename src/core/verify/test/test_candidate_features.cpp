// The candidate features' chroma is measured from the frame's own (FrameChroma): known answers
// for the frame's chroma, and one scene under two lights that tint it differently giving the
// same chroma features.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

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

}  // namespace
}  // namespace rle_vision
