#include "rle_vision/verify/candidate_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_convert.h"
#include "verify/candidate_geometry.h"

namespace rle_vision {
namespace {

constexpr int kPatch = 16;      // the appearance patch: the box plus a margin, resized to 16x16
constexpr int kCell = 8;        // gradient orientation cells: 2x2 of 8x8 px
constexpr int kOrientations = 8;
constexpr int kChromaGrid = 4;  // U and V averaged on a 4x4 grid
constexpr int kRingGrid = 32;   // the box and its ring's colours: sampled on a 32x32 grid
constexpr int kChromaReferenceGrid = 48;  // the frame's chroma: the median of a 48x48 grid of pixels

// `area` of `bgr` sampled onto the kRingGrid x kRingGrid grid as cv::resize's INTER_NEAREST
// samples it (the same pixels: its own arithmetic), without its per-call set-up.
void nearestGrid(const cv::Mat& bgr, const cv::Rect& area, cv::Mat* grid) {
  grid->create(kRingGrid, kRingGrid, CV_8UC3);
  const double fx = 1. / (static_cast<double>(kRingGrid) / area.width);
  const double fy = 1. / (static_cast<double>(kRingGrid) / area.height);
  std::array<int, kRingGrid> column;
  for (int x = 0; x < kRingGrid; ++x) column[x] = 3 * (area.x + std::min(cvFloor(x * fx), area.width - 1));
  for (int y = 0; y < kRingGrid; ++y) {
    const uint8_t* from = bgr.ptr<uint8_t>(area.y + std::min(cvFloor(y * fy), area.height - 1));
    uint8_t* to = grid->ptr<uint8_t>(y);
    for (int x = 0; x < kRingGrid; ++x, to += 3) {
      const uint8_t* p = from + column[x];
      to[0] = p[0], to[1] = p[1], to[2] = p[2];
    }
  }
}

// Mean and standard deviation of the YUV pixels of `grid` (kRingGrid x kRingGrid) inside `inner`
// (the box) and outside it (the ring). Sums per byte position of a row first (contiguous: the
// compiler vectorises them), then per channel; the ring's are the whole grid's less the box's.
void yuvStats(const cv::Mat& grid, const cv::Rect& inner, double box_mean[3], double box_sd[3], double ring_mean[3],
              double ring_sd[3]) {
  constexpr int kRowBytes = 3 * kRingGrid;
  int32_t all_sum[kRowBytes] = {}, all_sq[kRowBytes] = {}, in_sum[kRowBytes] = {}, in_sq[kRowBytes] = {};
  const int x0 = std::clamp(inner.x, 0, kRingGrid), x1 = std::clamp(inner.x + inner.width, x0, kRingGrid);
  const int y0 = std::clamp(inner.y, 0, kRingGrid), y1 = std::clamp(inner.y + inner.height, y0, kRingGrid);
  for (int y = 0; y < kRingGrid; ++y) {
    const uint8_t* row = grid.ptr<uint8_t>(y);
    for (int i = 0; i < kRowBytes; ++i) {
      const int32_t v = row[i];
      all_sum[i] += v;
      all_sq[i] += v * v;
    }
    if (y < y0 || y >= y1) continue;
    for (int i = 3 * x0; i < 3 * x1; ++i) {
      const int32_t v = row[i];
      in_sum[i] += v;
      in_sq[i] += v * v;
    }
  }
  int64_t sum[2][3] = {}, sum2[2][3] = {};
  for (int i = 0; i < kRowBytes; ++i) {
    sum[0][i % 3] += in_sum[i];
    sum2[0][i % 3] += in_sq[i];
    sum[1][i % 3] += all_sum[i] - in_sum[i];
    sum2[1][i % 3] += all_sq[i] - in_sq[i];
  }
  const size_t box_n = static_cast<size_t>((x1 - x0) * (y1 - y0));
  const size_t n[2] = {box_n, static_cast<size_t>(kRingGrid * kRingGrid) - box_n};
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

// COLOR_BGR2GRAY's grey level (15-bit fixed point, bit-exact; not YUV's Y, which rounds
// otherwise now and then).
inline int greyLevel(int b, int g, int r) { return (r * 9798 + g * 19235 + b * 3735 + (1 << 14)) >> 15; }

// The unsigned orientation bin of gradient (gx, gy): atan2(gy, gx) folded into [0, pi) and cut
// into kOrientations (8) equal bins. Found by comparing |gy| with |gx| times the tangents of the
// bins' edges within a quadrant (atan2 was a fifth of the features' cost); a gradient within
// rounding of an edge (equal |gx| and |gy| are common: the 45 degree edge) takes atan2's own
// bin, so the bins are atan2's, always.
inline int orientationBin(float gx, float gy) {
  static_assert(kOrientations == 8, "the quadrant's edges below are those of 8 bins");
  const float a = std::abs(gx), b = std::abs(gy);
  const float below = 0.41421356f * a, above = 2.41421356f * a;  // tan(pi/8), tan(3 pi/8)
  // On an axis, atan2's bins: float(pi / 2) lies just above pi / 2; float(pi) above pi.
  if (b == 0) return gx < 0 ? kOrientations - 1 : 0;
  if (a == 0) return kOrientations / 2;
  const float tie = 1e-4f * (a + b);
  if (a <= tie || b <= tie || std::abs(b - below) <= tie || std::abs(b - a) <= tie || std::abs(b - above) <= tie) {
    float angle = std::atan2(gy, gx);
    if (angle < 0) angle += static_cast<float>(M_PI);
    return std::min(kOrientations - 1, static_cast<int>(angle / M_PI * kOrientations));
  }
  const int in_quadrant = (b > below) + (b > a) + (b > above);
  // Folded into [0, pi): the first quadrant when gx and gy have one sign, else the second.
  return (gx > 0) == (gy > 0) ? in_quadrant : kOrientations - 1 - in_quadrant;
}

// Gradient orientation histograms (unsigned, magnitude-weighted) of the grey patch (kPatch x
// kPatch floats) per cell, the whole descriptor L2-normalised.
void orientations(const float* grey, float* out) {
  std::fill(out, out + (kPatch / kCell) * (kPatch / kCell) * kOrientations, 0.0f);
  for (int y = 1; y < kPatch - 1; ++y) {
    const float* row = grey + y * kPatch;
    for (int x = 1; x < kPatch - 1; ++x) {
      const float gx = row[x + 1] - row[x - 1];
      const float gy = row[x + kPatch] - row[x - kPatch];
      const float magnitude = std::sqrt(gx * gx + gy * gy);
      out[((y / kCell) * (kPatch / kCell) + x / kCell) * kOrientations + orientationBin(gx, gy)] += magnitude;
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
  candidate_geometry::shapeFeatures(r, bgr.size(), f);
  f += candidate_geometry::kShapeFeatureCount;
  // Colour: the box's, and a ring around it (half the box's larger side wide), sampled on a
  // 32x32 grid over the ring's outer box: the cost does not grow with the blob.
  const cv::Rect around = candidate_geometry::grown(r, 0.5, bgr.size());
  // The pixels are read in place: what cv::resize refused (a crop off the frame, another pixel
  // type) must be refused here.
  if (bgr.type() != CV_8UC3 || around.empty()) {
    throw std::invalid_argument("candidate features: the region's box lies off the frame, or the frame is not 8-bit BGR");
  }
  nearestGrid(bgr, around, &patch);
  cv::cvtColor(patch, yuv, cv::COLOR_BGR2YUV);
  const cv::Rect inner = candidate_geometry::boxOnGrid(candidate_geometry::box(r), around, kRingGrid);
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
  const cv::Rect appearance = candidate_geometry::grown(r, 0.25, bgr.size());
  cv::resize(bgr(appearance), patch, cv::Size(kPatch, kPatch), 0, 0,
             appearance.width <= 2 * kPatch && appearance.height <= 2 * kPatch ? cv::INTER_AREA : cv::INTER_LINEAR);
  // Its grey levels (COLOR_BGR2GRAY's, as floats in [0, 1]) and its chroma averaged on a 4x4
  // grid (COLOR_BGR2YUV's, then INTER_AREA's rounding), in one pass over the patch.
  std::array<float, kPatch * kPatch> grey;
  constexpr int kChromaCell = kPatch / kChromaGrid;
  int chroma_sum[2][kChromaGrid * kChromaGrid] = {};
  const float to_unit = static_cast<float>(1.0 / 255.0);
  for (int y = 0; y < kPatch; ++y) {
    const uint8_t* p = patch.ptr<uint8_t>(y);
    for (int x = 0; x < kPatch; ++x, p += 3) {
      const Channels yuv = yuvFromRgb(p[2], p[1], p[0]);
      grey[y * kPatch + x] = static_cast<float>(greyLevel(p[0], p[1], p[2])) * to_unit;
      const int cell = (y / kChromaCell) * kChromaGrid + x / kChromaCell;
      chroma_sum[0][cell] += yuv[1];
      chroma_sum[1][cell] += yuv[2];
    }
  }
  orientations(grey.data(), f);
  f += (kPatch / kCell) * (kPatch / kCell) * kOrientations;
  const float cell_area = 1.0f / (kChromaCell * kChromaCell);
  for (int c = 1; c <= 2; ++c) {
    for (int cell = 0; cell < kChromaGrid * kChromaGrid; ++cell) {
      const int mean = cv::saturate_cast<uint8_t>(static_cast<float>(chroma_sum[c - 1][cell]) * cell_area);
      *f++ = static_cast<float>((mean - shift[c]) / 255.0);
    }
  }
}

}  // namespace rle_vision
