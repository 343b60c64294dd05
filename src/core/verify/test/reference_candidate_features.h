// The candidate features as first written, one OpenCV call per step (resize, cvtColor,
// convertTo, atan2): the reference the fast path (candidate_features.cpp, which reads the pixels
// it needs in place) must equal bit for bit, so that a model trained on either holds on both.
// Grey is COLOR_BGR2GRAY's 15-bit fixed point, written out: what OpenCV 4.6 computes, and what
// the shipped model was trained on.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "rle_vision/verify/candidate_features.h"

namespace rle_vision {
namespace reference {

constexpr int kPatch = 16, kCell = 8, kOrientations = 8, kChromaGrid = 4, kRingGrid = 32;

inline cv::Rect grown(const Region& r, double margin, const cv::Size& size) {
  const int w = r.right - r.left + 1, h = r.bottom - r.top + 1;
  const int m = std::max(2, static_cast<int>(std::lround(margin * std::max(w, h))));
  return cv::Rect(r.left - m, r.top - m, w + 2 * m, h + 2 * m) & cv::Rect(cv::Point(), size);
}

inline void yuvStats(const cv::Mat& grid, const cv::Rect& inner, double mean[2][3], double sd[2][3]) {
  int64_t sum[2][3] = {}, sum2[2][3] = {};
  size_t n[2] = {0, 0};
  for (int y = 0; y < grid.rows; ++y) {
    for (int x = 0; x < grid.cols; ++x) {
      const int which = inner.contains(cv::Point(x, y)) ? 0 : 1;
      const cv::Vec3b yuv = grid.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) sum[which][c] += yuv[c], sum2[which][c] += yuv[c] * yuv[c];
      ++n[which];
    }
  }
  for (int which = 0; which < 2; ++which) {
    for (int c = 0; c < 3; ++c) {
      mean[which][c] = n[which] ? static_cast<double>(sum[which][c]) / n[which] : 0;
      sd[which][c] = n[which] ? std::sqrt(std::max(0.0, static_cast<double>(sum2[which][c]) / n[which] -
                                                            mean[which][c] * mean[which][c]))
                              : 0;
    }
  }
}

inline void orientations(const cv::Mat& grey, float* out) {
  const int count = (kPatch / kCell) * (kPatch / kCell) * kOrientations;
  std::fill(out, out + count, 0.0f);
  for (int y = 1; y < kPatch - 1; ++y) {
    for (int x = 1; x < kPatch - 1; ++x) {
      const float gx = grey.at<float>(y, x + 1) - grey.at<float>(y, x - 1);
      const float gy = grey.at<float>(y + 1, x) - grey.at<float>(y - 1, x);
      float angle = std::atan2(gy, gx);
      if (angle < 0) angle += static_cast<float>(M_PI);
      const int bin = std::min(kOrientations - 1, static_cast<int>(angle / M_PI * kOrientations));
      out[((y / kCell) * (kPatch / kCell) + x / kCell) * kOrientations + bin] += std::sqrt(gx * gx + gy * gy);
    }
  }
  double norm = 1e-6;
  for (int i = 0; i < count; ++i) norm += out[i] * out[i];
  norm = std::sqrt(norm);
  for (int i = 0; i < count; ++i) out[i] = static_cast<float>(out[i] / norm);
}

inline cv::Mat greyOf(const cv::Mat& bgr) {
  cv::Mat grey(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      grey.at<uint8_t>(y, x) = static_cast<uint8_t>((p[2] * 9798 + p[1] * 19235 + p[0] * 3735 + (1 << 14)) >> 15);
    }
  }
  return grey;
}

inline void candidateFeatures(const cv::Mat& bgr, const FrameChroma& frame, const Region& r, CandidateFeatures* out) {
  float* f = out->data();
  const double w = r.right - r.left + 1, h = r.bottom - r.top + 1;
  const double trace = r.var_xx + r.var_yy, det = r.var_xx * r.var_yy - r.var_xy * r.var_xy;
  const double disc = std::sqrt(std::max(0.0, trace * trace / 4 - det));
  const double major = trace / 2 + disc, minor = std::max(0.0, trace / 2 - disc);
  *f++ = static_cast<float>(std::log(std::max<uint32_t>(1, r.area)));
  *f++ = static_cast<float>(r.area / (w * h));
  *f++ = static_cast<float>(std::log(w / h));
  *f++ = static_cast<float>(major > 0 ? std::sqrt(minor / major) : 1.0);
  *f++ = static_cast<float>(r.cy / std::max(1, bgr.rows));
  *f++ = static_cast<float>(r.cx / std::max(1, bgr.cols));
  const cv::Rect box(r.left, r.top, static_cast<int>(w), static_cast<int>(h));
  const cv::Rect around = grown(r, 0.5, bgr.size());
  cv::Mat grid, yuv;
  cv::resize(bgr(around), grid, cv::Size(kRingGrid, kRingGrid), 0, 0, cv::INTER_NEAREST);
  cv::cvtColor(grid, yuv, cv::COLOR_BGR2YUV);
  const double sx = static_cast<double>(kRingGrid) / around.width, sy = static_cast<double>(kRingGrid) / around.height;
  const cv::Rect inner(static_cast<int>(std::floor((box.x - around.x) * sx)), static_cast<int>(std::floor((box.y - around.y) * sy)),
                       std::max(1, static_cast<int>(std::ceil(box.width * sx))), std::max(1, static_cast<int>(std::ceil(box.height * sy))));
  double mean[2][3], sd[2][3];
  yuvStats(yuv, inner, mean, sd);
  const double shift[3] = {0, frame.u - 128, frame.v - 128};
  for (int which = 0; which < 2; ++which) {
    for (int c = 1; c <= 2; ++c) mean[which][c] -= shift[c];
  }
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>(mean[0][c] / 255.0);
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>(sd[0][c] / 255.0);
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>(mean[1][c] / 255.0);
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>((mean[0][c] - mean[1][c]) / 255.0);
  const cv::Rect appearance = grown(r, 0.25, bgr.size());
  cv::Mat patch, grey, chroma;
  cv::resize(bgr(appearance), patch, cv::Size(kPatch, kPatch), 0, 0,
             appearance.width <= 2 * kPatch && appearance.height <= 2 * kPatch ? cv::INTER_AREA : cv::INTER_LINEAR);
  greyOf(patch).convertTo(grey, CV_32F, 1.0 / 255.0);
  orientations(grey, f);
  f += (kPatch / kCell) * (kPatch / kCell) * kOrientations;
  cv::cvtColor(patch, chroma, cv::COLOR_BGR2YUV);
  cv::resize(chroma, chroma, cv::Size(kChromaGrid, kChromaGrid), 0, 0, cv::INTER_AREA);
  for (int c = 1; c <= 2; ++c) {
    for (int y = 0; y < kChromaGrid; ++y) {
      for (int x = 0; x < kChromaGrid; ++x) *f++ = static_cast<float>((chroma.at<cv::Vec3b>(y, x)[c] - shift[c]) / 255.0);
    }
  }
}

}  // namespace reference
}  // namespace rle_vision
