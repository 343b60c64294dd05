// The candidate features' pixel work as first written, one OpenCV call per step (resize,
// cvtColor, convertTo, atan2): the reference the fast path (candidate_features.cpp, which reads
// the pixels it needs in place) must equal bit for bit, so that a model trained on either holds
// on both. The blob's geometry (verify/candidate_geometry.h) is the features' own.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "rle_vision/verify/candidate_features.h"
#include "verify/candidate_geometry.h"

namespace rle_vision {
namespace reference {

constexpr int kPatch = 16, kCell = 8, kOrientations = 8, kChromaGrid = 4, kRingGrid = 32;

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

inline void candidateFeatures(const cv::Mat& bgr, const FrameChroma& frame, const Region& r, CandidateFeatures* out) {
  float* f = out->data();
  candidate_geometry::shapeFeatures(r, bgr.size(), f);
  f += candidate_geometry::kShapeFeatureCount;
  const cv::Rect around = candidate_geometry::grown(r, 0.5, bgr.size());
  cv::Mat grid, yuv;
  cv::resize(bgr(around), grid, cv::Size(kRingGrid, kRingGrid), 0, 0, cv::INTER_NEAREST);
  cv::cvtColor(grid, yuv, cv::COLOR_BGR2YUV);
  const cv::Rect inner = candidate_geometry::boxOnGrid(candidate_geometry::box(r), around, kRingGrid);
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
  const cv::Rect appearance = candidate_geometry::grown(r, 0.25, bgr.size());
  cv::Mat patch, grey, chroma;
  cv::resize(bgr(appearance), patch, cv::Size(kPatch, kPatch), 0, 0,
             appearance.width <= 2 * kPatch && appearance.height <= 2 * kPatch ? cv::INTER_AREA : cv::INTER_LINEAR);
  cv::cvtColor(patch, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F, 1.0 / 255.0);
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
