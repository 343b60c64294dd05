// The display conversion: a camera's 4:2:2 frames through OpenCV's video-range decode, every
// format into a buffer kept across frames (the tracker converts every frame with candidates for
// its verifier).
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_convert.h"
#include "rle_vision/pipeline/overlay.h"

namespace rle_vision {
namespace {

TEST(Overlay, DisplayConversionReusesItsBufferFrameAfterFrame) {
  cv::Mat bgr(48, 64, CV_8UC3);
  cv::RNG rng(3);
  rng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
  const cv::Mat uyvy = bgrToUyvy(bgr);
  cv::Mat expected;
  cv::cvtColor(uyvy, expected, cv::COLOR_YUV2BGR_UYVY);
  cv::Mat buffer;
  toDisplayBgr(uyvy, PixelFormat::UYVY, &buffer);
  const uint8_t* data = buffer.data;
  for (int frame = 0; frame < 3; ++frame) {
    toDisplayBgr(uyvy, PixelFormat::UYVY, &buffer);
    EXPECT_EQ(buffer.data, data) << "frame " << frame << ": a new buffer";
    EXPECT_EQ(cv::norm(buffer, expected, cv::NORM_INF), 0);
  }
  // The returning form gives the same pixels; bgr8 is copied, not shared.
  EXPECT_EQ(cv::norm(toDisplayBgr(uyvy, PixelFormat::UYVY), expected, cv::NORM_INF), 0);
  toDisplayBgr(bgr, PixelFormat::BGR8, &buffer);
  EXPECT_EQ(cv::norm(buffer, bgr, cv::NORM_INF), 0);
  EXPECT_NE(buffer.data, bgr.data);  // a copy to draw on, never the frame itself
  EXPECT_EQ(buffer.data, data);      // in the same buffer, every format alike
  cv::Mat rgb, grey;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  toDisplayBgr(rgb, PixelFormat::RGB8, &buffer);
  EXPECT_EQ(cv::norm(buffer, bgr, cv::NORM_INF), 0);
  EXPECT_EQ(buffer.data, data);
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  toDisplayBgr(grey, PixelFormat::MONO8, &buffer);
  EXPECT_EQ(buffer.data, data);
}

}  // namespace
}  // namespace rle_vision
