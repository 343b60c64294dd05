// Pixel layouts the core accepts, named after their ROS image encodings.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace rle_vision {

enum class PixelFormat {
  BGR8,  // "bgr8"
  RGB8,  // "rgb8"
  MONO8,  // "mono8"
  UYVY,  // "yuv422" (ROS's name for UYVY 4:2:2)
  YUYV,  // "yuv422_yuy2"
};

// Maps a sensor_msgs/Image encoding to a format. Returns false for unsupported encodings.
bool pixelFormatFromEncoding(const std::string& encoding, PixelFormat* format);
const char* encodingOf(PixelFormat format);
// The encodings accepted, for error messages: "bgr8, rgb8, mono8, yuv422, yuv422_yuy2".
const char* supportedEncodings();

// The largest image processed (4096 x 4096 pixels, any shape): a bigger one is almost surely a
// broken or misconfigured driver, and would cost hundreds of MB and seconds per frame.
constexpr long long kMaxImagePixels = 4096LL * 4096LL;

// Checks that an image can be processed as `format`. Returns "" when it can, otherwise a
// sentence saying what is wrong (empty or too large image, wrong channel count or depth, odd
// width for 4:2:2).
std::string checkImage(const cv::Mat& image, PixelFormat format);
// The same size checks on a width and height alone (before looking at the pixels).
std::string checkImageSize(long long width, long long height);

}  // namespace rle_vision
