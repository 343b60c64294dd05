#include "rle_vision/color/color_convert.h"

#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/simd_dispatch.h"

namespace rle_vision {

RLE_VISION_HOT
void bgrRowToYuvPlanes(const uint8_t* src, int width, bool src_is_rgb, uint8_t* y_out,
                       uint8_t* u_out, uint8_t* v_out) {
  using namespace yuv_fixed_point;
  const int r_index = src_is_rgb ? 0 : 2;
  const int b_index = 2 - r_index;
  for (int x = 0; x < width; ++x) {
    const int r = src[3 * x + r_index];
    const int g = src[3 * x + 1];
    const int b = src[3 * x + b_index];
    const int y = (r * kR2Y + g * kG2Y + b * kB2Y + kRound) >> kShift;
    int u = ((b - y) * kB2U + kDelta + kRound) >> kShift;
    int v = ((r - y) * kR2V + kDelta + kRound) >> kShift;
    u = u < 0 ? 0 : (u > 255 ? 255 : u);
    v = v < 0 ? 0 : (v > 255 ? 255 : v);
    y_out[x] = static_cast<uint8_t>(y);  // y is always within 0..255
    u_out[x] = static_cast<uint8_t>(u);
    v_out[x] = static_cast<uint8_t>(v);
  }
}

RLE_VISION_HOT
void interleavedRowToPlanes(const uint8_t* src, int width, uint8_t* c0, uint8_t* c1, uint8_t* c2) {
  for (int x = 0; x < width; ++x) {
    c0[x] = src[3 * x];
    c1[x] = src[3 * x + 1];
    c2[x] = src[3 * x + 2];
  }
}

void bgrRowToRgbPlanes(const uint8_t* src, int width, bool src_is_rgb, uint8_t* r, uint8_t* g,
                       uint8_t* b) {
  if (src_is_rgb) {
    interleavedRowToPlanes(src, width, r, g, b);
  } else {
    interleavedRowToPlanes(src, width, b, g, r);
  }
}

RLE_VISION_HOT
void yuv422RowToPlanes(const uint8_t* src, int width, bool is_uyvy, uint8_t* y, uint8_t* u,
                       uint8_t* v) {
  // UYVY: U0 Y0 V0 Y1; YUYV: Y0 U0 Y1 V0.
  const int y_offset = is_uyvy ? 1 : 0;
  const int c_offset = is_uyvy ? 0 : 1;
  for (int pair = 0; pair < width / 2; ++pair) {
    const uint8_t* p = src + 4 * pair;
    y[2 * pair] = p[y_offset];
    y[2 * pair + 1] = p[y_offset + 2];
    u[2 * pair] = u[2 * pair + 1] = p[c_offset];
    v[2 * pair] = v[2 * pair + 1] = p[c_offset + 2];
  }
}

Channels convertBgrPixel(uint8_t b, uint8_t g, uint8_t r, ColorSpace space) {
  switch (space) {
    case ColorSpace::YUV: return yuvFromRgb(r, g, b);
    case ColorSpace::RGB: return Channels{{r, g, b}};
    case ColorSpace::HSV: {
      cv::Mat pixel(1, 1, CV_8UC3, cv::Scalar(b, g, r));
      cv::Mat hsv;
      cv::cvtColor(pixel, hsv, cv::COLOR_BGR2HSV);
      const cv::Vec3b h = hsv.at<cv::Vec3b>(0, 0);
      return Channels{{h[0], h[1], h[2]}};
    }
  }
  return Channels{{0, 0, 0}};
}

cv::Mat convertBgrImage(const cv::Mat& bgr, ColorSpace space) {
  if (bgr.type() != CV_8UC3) throw std::invalid_argument("convertBgrImage needs a CV_8UC3 image");
  cv::Mat out;
  switch (space) {
    case ColorSpace::YUV: cv::cvtColor(bgr, out, cv::COLOR_BGR2YUV); break;
    case ColorSpace::RGB: cv::cvtColor(bgr, out, cv::COLOR_BGR2RGB); break;
    case ColorSpace::HSV: cv::cvtColor(bgr, out, cv::COLOR_BGR2HSV); break;
  }
  return out;
}

cv::Mat bgrToUyvy(const cv::Mat& bgr) {
  if (bgr.type() != CV_8UC3 || bgr.cols % 2 != 0) {
    throw std::invalid_argument("bgrToUyvy needs a CV_8UC3 image of even width");
  }
  cv::Mat uyvy(bgr.rows, bgr.cols, CV_8UC2);
  for (int row = 0; row < bgr.rows; ++row) {
    const uint8_t* s = bgr.ptr<uint8_t>(row);
    uint8_t* d = uyvy.ptr<uint8_t>(row);
    for (int pair = 0; pair < bgr.cols / 2; ++pair) {
      const uint8_t* p0 = s + 6 * pair;
      const Channels a = yuvFromRgb(p0[2], p0[1], p0[0]);
      const Channels b = yuvFromRgb(p0[5], p0[4], p0[3]);
      d[4 * pair + 0] = pairMean(a[1], b[1]);
      d[4 * pair + 1] = a[0];
      d[4 * pair + 2] = pairMean(a[2], b[2]);
      d[4 * pair + 3] = b[0];
    }
  }
  return uyvy;
}

cv::Mat yuv422ToBgr(const cv::Mat& packed, bool is_uyvy) {
  if (packed.type() != CV_8UC2 || packed.cols % 2 != 0) {
    throw std::invalid_argument("yuv422ToBgr needs a CV_8UC2 4:2:2 image of even width");
  }
  cv::Mat yuv(packed.size(), CV_8UC3);
  std::vector<uint8_t> y(packed.cols), u(packed.cols), v(packed.cols);
  for (int row = 0; row < packed.rows; ++row) {
    yuv422RowToPlanes(packed.ptr<uint8_t>(row), packed.cols, is_uyvy, y.data(), u.data(), v.data());
    cv::Vec3b* out = yuv.ptr<cv::Vec3b>(row);
    for (int x = 0; x < packed.cols; ++x) out[x] = cv::Vec3b(y[x], u[x], v[x]);
  }
  cv::Mat bgr;
  cv::cvtColor(yuv, bgr, cv::COLOR_YUV2BGR);  // the inverse of the COLOR_BGR2YUV above
  return bgr;
}

cv::Mat frameToBgr(const cv::Mat& image, PixelFormat format) {
  cv::Mat bgr;
  switch (format) {
    case PixelFormat::BGR8: bgr = image.clone(); break;
    case PixelFormat::RGB8: cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR); break;
    case PixelFormat::MONO8: cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR); break;
    case PixelFormat::UYVY: bgr = yuv422ToBgr(image, true); break;
    case PixelFormat::YUYV: bgr = yuv422ToBgr(image, false); break;
  }
  return bgr;
}

}  // namespace rle_vision
