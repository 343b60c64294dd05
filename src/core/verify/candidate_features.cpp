#include "rle_vision/verify/candidate_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace rle_vision {
namespace {

constexpr int kPatch = 16;      // the appearance patch: the box plus a margin, resized to 16x16
constexpr int kCell = 8;        // gradient orientation cells: 2x2 of 8x8 px
constexpr int kOrientations = 8;
constexpr int kChromaGrid = 4;  // U and V averaged on a 4x4 grid
constexpr int kRingGrid = 32;   // the box and its ring's colours: sampled on a 32x32 grid
constexpr int kChromaReferenceGrid = 48;  // the frame's chroma: the median of a 48x48 grid of pixels

// The box grown by `margin` (a share of its larger side, at least 2 px), clipped to the image.
cv::Rect grown(const Region& r, double margin, const cv::Size& size) {
  const int w = r.right - r.left + 1, h = r.bottom - r.top + 1;
  const int m = std::max(2, static_cast<int>(std::lround(margin * std::max(w, h))));
  return cv::Rect(r.left - m, r.top - m, w + 2 * m, h + 2 * m) & cv::Rect(cv::Point(), size);
}

// Mean and standard deviation of the YUV pixels of `grid` inside `inner` (box) and outside it
// (ring), in one pass.
void yuvStats(const cv::Mat& grid, const cv::Rect& inner, double box_mean[3], double box_sd[3], double ring_mean[3],
              double ring_sd[3]) {
  int64_t sum[2][3] = {}, sum2[2][3] = {};
  size_t n[2] = {0, 0};
  for (int y = 0; y < grid.rows; ++y) {
    const uint8_t* row = grid.ptr<uint8_t>(y);
    const bool rows_inner = y >= inner.y && y < inner.y + inner.height;
    const int x0 = rows_inner ? std::clamp(inner.x, 0, grid.cols) : grid.cols;
    const int x1 = rows_inner ? std::clamp(inner.x + inner.width, x0, grid.cols) : grid.cols;
    auto add = [&](int from, int to, int which) {
      for (int x = from; x < to; ++x) {
        const uint8_t* yuv = row + 3 * x;
        for (int c = 0; c < 3; ++c) {
          const int v = yuv[c];
          sum[which][c] += v;
          sum2[which][c] += v * v;
        }
      }
      n[which] += static_cast<size_t>(std::max(0, to - from));
    };
    add(0, x0, 1);
    add(x0, x1, 0);
    add(x1, grid.cols, 1);
  }
  double* means[2] = {box_mean, ring_mean};
  double* sds[2] = {box_sd, ring_sd};
  for (int which = 0; which < 2; ++which) {
    for (int c = 0; c < 3; ++c) {
      const double mean = n[which] ? static_cast<double>(sum[which][c]) / n[which] : 0;
      means[which][c] = mean;
      sds[which][c] = n[which] ? std::sqrt(std::max(0.0, static_cast<double>(sum2[which][c]) / n[which] - mean * mean)) : 0;
    }
  }
}

// Gradient orientation histograms (unsigned, magnitude-weighted) of the grey patch per cell,
// the whole descriptor L2-normalised.
void orientations(const cv::Mat& grey, float* out) {
  std::fill(out, out + (kPatch / kCell) * (kPatch / kCell) * kOrientations, 0.0f);
  for (int y = 1; y < kPatch - 1; ++y) {
    for (int x = 1; x < kPatch - 1; ++x) {
      const float gx = grey.at<float>(y, x + 1) - grey.at<float>(y, x - 1);
      const float gy = grey.at<float>(y + 1, x) - grey.at<float>(y - 1, x);
      const float magnitude = std::sqrt(gx * gx + gy * gy);
      float angle = std::atan2(gy, gx);
      if (angle < 0) angle += static_cast<float>(M_PI);
      const int bin = std::min(kOrientations - 1, static_cast<int>(angle / M_PI * kOrientations));
      out[((y / kCell) * (kPatch / kCell) + x / kCell) * kOrientations + bin] += magnitude;
    }
  }
  const int count = (kPatch / kCell) * (kPatch / kCell) * kOrientations;
  double norm = 1e-6;
  for (int i = 0; i < count; ++i) norm += out[i] * out[i];
  norm = std::sqrt(norm);
  for (int i = 0; i < count; ++i) out[i] = static_cast<float>(out[i] / norm);
}

}  // namespace

FrameChroma frameChroma(const cv::Mat& bgr) {
  FrameChroma chroma;
  if (bgr.empty() || bgr.type() != CV_8UC3) return chroma;
  cv::Mat small, yuv;
  cv::resize(bgr, small, cv::Size(kChromaReferenceGrid, kChromaReferenceGrid), 0, 0, cv::INTER_NEAREST);
  cv::cvtColor(small, yuv, cv::COLOR_BGR2YUV);
  std::vector<uint8_t> values(static_cast<size_t>(yuv.total()));
  double* medians[2] = {&chroma.u, &chroma.v};
  for (int c = 1; c <= 2; ++c) {
    const uint8_t* p = yuv.ptr<uint8_t>();
    for (size_t i = 0; i < values.size(); ++i) values[i] = p[3 * i + c];
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    *medians[c - 1] = values[values.size() / 2];
  }
  return chroma;
}

void candidateFeatures(const cv::Mat& bgr, const FrameChroma& frame, const Region& r, CandidateFeatures* out,
                       cv::Mat* patch_bgr, cv::Mat* patch_yuv) {
  cv::Mat local_bgr, local_yuv;
  cv::Mat& patch = patch_bgr ? *patch_bgr : local_bgr;
  cv::Mat& yuv = patch_yuv ? *patch_yuv : local_yuv;
  float* f = out->data();
  const double w = r.right - r.left + 1, h = r.bottom - r.top + 1;
  // The blob: size, fill of its box, aspect, roundness (minor / major axis), row and column in
  // the view (size against row: where a ball of this size can be).
  const double trace = r.var_xx + r.var_yy, det = r.var_xx * r.var_yy - r.var_xy * r.var_xy;
  const double disc = std::sqrt(std::max(0.0, trace * trace / 4 - det));
  const double major = trace / 2 + disc, minor = std::max(0.0, trace / 2 - disc);
  *f++ = static_cast<float>(std::log(std::max<uint32_t>(1, r.area)));
  *f++ = static_cast<float>(r.area / (w * h));
  *f++ = static_cast<float>(std::log(w / h));
  *f++ = static_cast<float>(major > 0 ? std::sqrt(minor / major) : 1.0);
  *f++ = static_cast<float>(r.cy / std::max(1, bgr.rows));
  *f++ = static_cast<float>(r.cx / std::max(1, bgr.cols));
  // Colour: the box's, and a ring around it (half the box's larger side wide), sampled on a
  // 32x32 grid over the ring's outer box: the cost does not grow with the blob.
  const cv::Rect box(r.left, r.top, static_cast<int>(w), static_cast<int>(h));
  const cv::Rect around = grown(r, 0.5, bgr.size());
  cv::resize(bgr(around), patch, cv::Size(kRingGrid, kRingGrid), 0, 0, cv::INTER_NEAREST);
  cv::cvtColor(patch, yuv, cv::COLOR_BGR2YUV);
  const double sx = static_cast<double>(kRingGrid) / around.width, sy = static_cast<double>(kRingGrid) / around.height;
  const cv::Rect inner(static_cast<int>(std::floor((box.x - around.x) * sx)), static_cast<int>(std::floor((box.y - around.y) * sy)),
                       std::max(1, static_cast<int>(std::ceil(box.width * sx))), std::max(1, static_cast<int>(std::ceil(box.height * sy))));
  double box_mean[3], box_sd[3], ring_mean[3], ring_sd[3];
  yuvStats(yuv, inner, box_mean, box_sd, ring_mean, ring_sd);
  // Chroma from the frame's (the box's minus the ring's is the same either way).
  const double shift[3] = {0, frame.u - 128, frame.v - 128};
  for (int c = 1; c <= 2; ++c) {
    box_mean[c] -= shift[c];
    ring_mean[c] -= shift[c];
  }
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>(box_mean[c] / 255.0);
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>(box_sd[c] / 255.0);
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>(ring_mean[c] / 255.0);
  for (int c = 0; c < 3; ++c) *f++ = static_cast<float>((box_mean[c] - ring_mean[c]) / 255.0);
  // Appearance: the box plus a quarter margin, 16x16 (small boxes averaged, large ones sampled).
  const cv::Rect appearance = grown(r, 0.25, bgr.size());
  cv::resize(bgr(appearance), patch, cv::Size(kPatch, kPatch), 0, 0,
             appearance.width <= 2 * kPatch && appearance.height <= 2 * kPatch ? cv::INTER_AREA : cv::INTER_LINEAR);
  cv::Mat grey;
  cv::cvtColor(patch, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F, 1.0 / 255.0);
  orientations(grey, f);
  f += (kPatch / kCell) * (kPatch / kCell) * kOrientations;
  cv::Mat chroma;
  cv::cvtColor(patch, chroma, cv::COLOR_BGR2YUV);
  cv::resize(chroma, chroma, cv::Size(kChromaGrid, kChromaGrid), 0, 0, cv::INTER_AREA);
  for (int c = 1; c <= 2; ++c) {
    for (int y = 0; y < kChromaGrid; ++y) {
      for (int x = 0; x < kChromaGrid; ++x) *f++ = static_cast<float>((chroma.at<cv::Vec3b>(y, x)[c] - shift[c]) / 255.0);
    }
  }
}

}  // namespace rle_vision
