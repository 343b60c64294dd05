// Colour conversions used by the classifier, the simulator and the colour learner.
// YUV is OpenCV's COLOR_BGR2YUV (fixed point, bit-exact with cv::cvtColor): classes tuned
// with OpenCV tools work unchanged.
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/color/pixel_format.h"

namespace rle_vision {

namespace yuv_fixed_point {
constexpr int kShift = 14;
constexpr int kRound = 1 << (kShift - 1);
constexpr int kR2Y = 4899, kG2Y = 9617, kB2Y = 1868;  // 0.299, 0.587, 0.114 * 2^14
constexpr int kB2U = 8061;   // 0.492 * 2^14
constexpr int kR2V = 14369;  // 0.877 * 2^14
constexpr int kDelta = 128 << kShift;
}  // namespace yuv_fixed_point

inline uint8_t saturateToByte(int v) { return static_cast<uint8_t>(v < 0 ? 0 : (v > 255 ? 255 : v)); }

// A pixel pair's shared chroma, as 4:2:2 holds it: the mean rounded up (what _mm256_avg_epu8 gives).
inline uint8_t pairMean(int a, int b) { return static_cast<uint8_t>((a + b + 1) >> 1); }

inline Channels yuvFromRgb(int r, int g, int b) {
  using namespace yuv_fixed_point;
  const int y = (r * kR2Y + g * kG2Y + b * kB2Y + kRound) >> kShift;
  const int u = ((b - y) * kB2U + kDelta + kRound) >> kShift;
  const int v = ((r - y) * kR2V + kDelta + kRound) >> kShift;
  return Channels{{saturateToByte(y), saturateToByte(u), saturateToByte(v)}};
}

// One BGR pixel in `space` (channel order of that space: Y,U,V / R,G,B / H,S,V).
Channels convertBgrPixel(uint8_t b, uint8_t g, uint8_t r, ColorSpace space);

// A whole CV_8UC3 BGR image in `space` (CV_8UC3, that space's channel order).
cv::Mat convertBgrImage(const cv::Mat& bgr, ColorSpace space);

// BGR (CV_8UC3, even width) to UYVY (CV_8UC2, ROS "yuv422") with the YUV above; each pixel
// pair shares the rounded mean of its two chroma values.
cv::Mat bgrToUyvy(const cv::Mat& bgr);

// A camera's 4:2:2 frame (CV_8UC2; UYVY when is_uyvy, else YUYV) as BGR whose
// convertBgrImage(..., YUV) is the camera's own YUV (within rounding): the YUV the tracker
// classifies on such frames. OpenCV's COLOR_YUV2BGR_UYVY reads limited-range video YUV and
// would shift a range measured on its output.
cv::Mat yuv422ToBgr(const cv::Mat& packed, bool is_uyvy);

// A camera frame as BGR (a new buffer) whose convertBgrImage(..., YUV) is the YUV the tracker
// classifies: where colours are measured for the tracker (learning, calibration). 4:2:2 frames
// through yuv422ToBgr, the others with OpenCV's conversions.
cv::Mat frameToBgr(const cv::Mat& image, PixelFormat format);

// Row helpers used by the classifier: split `width` interleaved pixels into planes.
// `src_is_rgb` tells whether the source is R,G,B (true) or B,G,R (false) ordered.
void bgrRowToYuvPlanes(const uint8_t* src, int width, bool src_is_rgb, uint8_t* y, uint8_t* u,
                       uint8_t* v);
void bgrRowToRgbPlanes(const uint8_t* src, int width, bool src_is_rgb, uint8_t* r, uint8_t* g,
                       uint8_t* b);
void interleavedRowToPlanes(const uint8_t* src, int width, uint8_t* c0, uint8_t* c1, uint8_t* c2);
// 4:2:2 row to full-resolution Y, U, V planes (chroma repeated for both pixels of a pair).
void yuv422RowToPlanes(const uint8_t* src, int width, bool is_uyvy, uint8_t* y, uint8_t* u,
                       uint8_t* v);

}  // namespace rle_vision
