#include "rle_vision/edges/sobel5.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/simd_dispatch.h"

namespace rle_vision {
namespace {

// OpenCV's BORDER_REFLECT_101 index (gfedcb|abcdefgh|gfedcba); a 1-long axis maps to 0.
inline int reflect101(int i, int length) {
  if (length == 1) return 0;
  while (i < 0 || i >= length) i = i < 0 ? -i : 2 * length - 2 - i;
  return i;
}

// One channel of a source row into a plane padded by 2 on each side (reflect-101).
void loadPaddedRow(const uint8_t* src, int width, int channels, int channel, int16_t* padded) {
  for (int x = 0; x < width; ++x) padded[x + 2] = src[x * channels + channel];
  for (int k = 1; k <= 2; ++k) {
    padded[2 - k] = src[reflect101(-k, width) * channels + channel];
    padded[width + 1 + k] = src[reflect101(width - 1 + k, width) * channels + channel];
  }
}

// All three channels of a BGR row at once (one pass over the interleaved bytes vectorises;
// three strided passes do not).
RLE_VISION_HOT
void deinterleave3(const uint8_t* __restrict src, int width, int16_t* __restrict p0, int16_t* __restrict p1,
                   int16_t* __restrict p2) {
  for (int x = 0; x < width; ++x) {
    p0[x] = src[3 * x];
    p1[x] = src[3 * x + 1];
    p2[x] = src[3 * x + 2];
  }
}

void loadPaddedRows3(const uint8_t* src, int width, int16_t* p0, int16_t* p1, int16_t* p2) {
  deinterleave3(src, width, p0 + 2, p1 + 2, p2 + 2);
  int16_t* planes[3] = {p0, p1, p2};
  for (int c = 0; c < 3; ++c) {
    for (int k = 1; k <= 2; ++k) {
      planes[c][2 - k] = src[reflect101(-k, width) * 3 + c];
      planes[c][width + 1 + k] = src[reflect101(width - 1 + k, width) * 3 + c];
    }
  }
}

// Vertical passes over five padded rows: smoothing [1 4 6 4 1] and derivative [-1 -2 0 2 1].
RLE_VISION_HOT
void verticalPass(const int16_t* __restrict r0, const int16_t* __restrict r1, const int16_t* __restrict r2,
                  const int16_t* __restrict r3, const int16_t* __restrict r4, int n,
                  int16_t* __restrict smooth, int16_t* __restrict derivative) {
  for (int x = 0; x < n; ++x) {
    smooth[x] = static_cast<int16_t>(r0[x] + 4 * r1[x] + 6 * r2[x] + 4 * r3[x] + r4[x]);
    derivative[x] = static_cast<int16_t>(r4[x] - r0[x] + 2 * (r3[x] - r1[x]));
  }
}

// Horizontal passes and the squared magnitude, kept where it beats the other channels
// (`best` starts at 0). Branch-free so it vectorises. gx and gy fit 16 bits (8-bit input:
// |gx|, |gy| <= 3 x 16 x 255 = 12240), so they are computed in 16-bit lanes, twice as many a
// vector as 32-bit ones; only the squares widen.
RLE_VISION_HOT
void horizontalPass(const int16_t* __restrict smooth, const int16_t* __restrict derivative, int width,
                    int32_t* __restrict best) {
  for (int x = 0; x < width; ++x) {
    const auto gx = static_cast<int16_t>(smooth[x + 4] - smooth[x] + 2 * (smooth[x + 3] - smooth[x + 1]));
    const auto gy = static_cast<int16_t>(derivative[x] + derivative[x + 4] +
                                         4 * (derivative[x + 1] + derivative[x + 3]) + 6 * derivative[x + 2]);
    const int32_t m2 = int32_t{gx} * gx + int32_t{gy} * gy;
    best[x] = best[x] > m2 ? best[x] : m2;
  }
}

RLE_VISION_HOT
void scaleToBytes(const int32_t* __restrict m2, int width, float scale, uint8_t* __restrict out) {
  for (int x = 0; x < width; ++x) {
    const float v = std::sqrt(static_cast<float>(m2[x])) * scale + 0.5f;
    out[x] = static_cast<uint8_t>(static_cast<int32_t>(std::min(v, 255.f)));
  }
}

}  // namespace

template <typename Sink>
void Sobel5::run(const cv::Mat& image, Sink sink) {
  if (image.empty() || (image.type() != CV_8UC3 && image.type() != CV_8UC1)) {
    throw std::invalid_argument("the 5x5 Sobel filter needs a non-empty CV_8UC3 or CV_8UC1 image");
  }
  width_ = image.cols;
  channels_ = image.channels();
  const int padded = width_ + 4;
  rows_.resize(static_cast<size_t>(5) * channels_ * padded);
  smooth_.resize(padded);
  derivative_.resize(padded);
  best_.resize(width_);
  auto ring = [&](int slot, int channel) { return rows_.data() + (static_cast<size_t>(slot) * channels_ + channel) * padded; };
  // Each source row is unpacked once, into ring slot (row + 2) mod 5.
  auto load = [&](int source_row, int slot) {
    const uint8_t* src = image.ptr<uint8_t>(reflect101(source_row, image.rows));
    if (channels_ == 3) {
      loadPaddedRows3(src, width_, ring(slot, 0), ring(slot, 1), ring(slot, 2));
    } else {
      for (int c = 0; c < channels_; ++c) loadPaddedRow(src, width_, channels_, c, ring(slot, c));
    }
  };
  for (int k = -2; k <= 1; ++k) load(k, (k + 5) % 5);
  for (int y = 0; y < image.rows; ++y) {
    load(y + 2, (y + 2) % 5);
    std::fill(best_.begin(), best_.end(), 0);
    for (int c = 0; c < channels_; ++c) {
      verticalPass(ring((y + 3) % 5, c), ring((y + 4) % 5, c), ring(y % 5, c), ring((y + 1) % 5, c),
                   ring((y + 2) % 5, c), padded, smooth_.data(), derivative_.data());
      horizontalPass(smooth_.data(), derivative_.data(), width_, best_.data());
    }
    sink(y, best_.data());
  }
}

void Sobel5::edges(const cv::Mat& image, double edge_gain, cv::Mat* edges) {
  if (!std::isfinite(edge_gain) || edge_gain <= 0) throw std::invalid_argument("edge gain must be a finite number > 0");
  edges->create(image.rows, image.cols, CV_8UC1);
  const float scale = static_cast<float>(edge_gain / kSobel5StepGain);
  run(image, [&](int y, const int32_t* m2) { scaleToBytes(m2, width_, scale, edges->ptr<uint8_t>(y)); });
}

void Sobel5::maxSquaredMagnitude(const cv::Mat& image, cv::Mat* magnitude2) {
  magnitude2->create(image.rows, image.cols, CV_32SC1);
  run(image, [&](int y, const int32_t* m2) { std::copy(m2, m2 + width_, magnitude2->ptr<int32_t>(y)); });
}

}  // namespace rle_vision
