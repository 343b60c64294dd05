#include "rle_vision/color/pixel_format.h"

namespace rle_vision {

bool pixelFormatFromEncoding(const std::string& encoding, PixelFormat* format) {
  if (encoding == "bgr8") {
    *format = PixelFormat::BGR8;
  } else if (encoding == "rgb8") {
    *format = PixelFormat::RGB8;
  } else if (encoding == "mono8" || encoding == "8UC1") {
    *format = PixelFormat::MONO8;
  } else if (encoding == "yuv422" || encoding == "uyvy") {
    *format = PixelFormat::UYVY;
  } else if (encoding == "yuv422_yuy2" || encoding == "yuyv") {
    *format = PixelFormat::YUYV;
  } else {
    return false;
  }
  return true;
}

const char* encodingOf(PixelFormat format) {
  switch (format) {
    case PixelFormat::BGR8: return "bgr8";
    case PixelFormat::RGB8: return "rgb8";
    case PixelFormat::MONO8: return "mono8";
    case PixelFormat::UYVY: return "yuv422";
    case PixelFormat::YUYV: return "yuv422_yuy2";
  }
  return "?";
}

const char* supportedEncodings() { return "bgr8, rgb8, mono8, yuv422 (UYVY), yuv422_yuy2 (YUYV)"; }

std::string checkImageSize(long long width, long long height) {
  if (width <= 0 || height <= 0) {
    return "the image is empty (" + std::to_string(width) + "x" + std::to_string(height) + " pixels)";
  }
  if (width * height > kMaxImagePixels) {
    return "the image is " + std::to_string(width) + "x" + std::to_string(height) + " pixels, more than the " +
           std::to_string(kMaxImagePixels) + " (4096x4096) processed; downscale it first (e.g. image_proc/crop_decimate)";
  }
  return "";
}

std::string checkImage(const cv::Mat& image, PixelFormat format) {
  if (image.empty() || image.cols <= 0 || image.rows <= 0) return "the image is empty (0 pixels)";
  const std::string size_problem = checkImageSize(image.cols, image.rows);
  if (!size_problem.empty()) return size_problem;
  if (image.depth() != CV_8U) return "the image depth is not 8-bit unsigned";
  int channels = 3;
  if (format == PixelFormat::MONO8) channels = 1;
  if (format == PixelFormat::UYVY || format == PixelFormat::YUYV) channels = 2;
  if (image.channels() != channels) {
    return std::string("encoding ") + encodingOf(format) + " needs " + std::to_string(channels) +
           " bytes per pixel but the image has " + std::to_string(image.channels());
  }
  if ((format == PixelFormat::UYVY || format == PixelFormat::YUYV) && image.cols % 2 != 0) {
    return "a 4:2:2 image must have an even width, got " + std::to_string(image.cols);
  }
  return "";
}

}  // namespace rle_vision
