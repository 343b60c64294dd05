// The geometry the candidate features share (private to the core): the blob's own shape
// features and the boxes around it that the colour and appearance features are measured on.
// One place for them, for the features and for the test's reference implementation of the
// pixel work (verify/test/reference_candidate_features.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/core.hpp>

#include "rle_vision/segment/regions.h"

namespace rle_vision {
namespace candidate_geometry {

// The blob's box grown by `margin` (a share of its larger side, at least 2 px), clipped to the
// image.
inline cv::Rect grown(const Region& r, double margin, const cv::Size& size) {
  const int w = r.right - r.left + 1, h = r.bottom - r.top + 1;
  const int m = std::max(2, static_cast<int>(std::lround(margin * std::max(w, h))));
  return cv::Rect(r.left - m, r.top - m, w + 2 * m, h + 2 * m) & cv::Rect(cv::Point(), size);
}

// The blob's box.
inline cv::Rect box(const Region& r) { return cv::Rect(r.left, r.top, r.right - r.left + 1, r.bottom - r.top + 1); }

// The blob's box in the cells of a grid x grid sampling of `around` (at least one cell).
inline cv::Rect boxOnGrid(const cv::Rect& box, const cv::Rect& around, int grid) {
  const double sx = static_cast<double>(grid) / around.width, sy = static_cast<double>(grid) / around.height;
  return cv::Rect(static_cast<int>(std::floor((box.x - around.x) * sx)), static_cast<int>(std::floor((box.y - around.y) * sy)),
                  std::max(1, static_cast<int>(std::ceil(box.width * sx))), std::max(1, static_cast<int>(std::ceil(box.height * sy))));
}

// The blob's 6 shape features into f: size, fill of its box, aspect, roundness (minor / major
// axis), row and column in the view (size against row: where a ball of this size can be).
inline void shapeFeatures(const Region& r, const cv::Size& frame, float* f) {
  const double w = r.right - r.left + 1, h = r.bottom - r.top + 1;
  const double trace = r.var_xx + r.var_yy, det = r.var_xx * r.var_yy - r.var_xy * r.var_xy;
  const double disc = std::sqrt(std::max(0.0, trace * trace / 4 - det));
  const double major = trace / 2 + disc, minor = std::max(0.0, trace / 2 - disc);
  f[0] = static_cast<float>(std::log(std::max<uint32_t>(1, r.area)));
  f[1] = static_cast<float>(r.area / (w * h));
  f[2] = static_cast<float>(std::log(w / h));
  f[3] = static_cast<float>(major > 0 ? std::sqrt(minor / major) : 1.0);
  f[4] = static_cast<float>(r.cy / std::max(1, frame.height));
  f[5] = static_cast<float>(r.cx / std::max(1, frame.width));
}
constexpr int kShapeFeatureCount = 6;

}  // namespace candidate_geometry
}  // namespace rle_vision
