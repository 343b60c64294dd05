#include "rle_vision/field/field_detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rle_vision/landmark/param_range.h"

namespace rle_vision {

std::string validateFieldOptions(const FieldOptions& o) {
  std::string problem;
#define RLE_FIELD_COLOR_PARAM(key, member, type, default_value, min, max, description) \
  if (problem.empty()) problem = outOfRange(#key, o.colour.member, min, max);
#define RLE_FIELD_BOUNDARY_PARAM(key, member, type, default_value, min, max, description) \
  if (problem.empty()) problem = outOfRange(#key, o.boundary.member, min, max);
#include "rle_vision/params/landmark_params.def"
  return problem;
}

void FieldDetector::setOptions(const FieldOptions& options) {
  model_ = FieldColorModel(options.colour);
  finder_ = FieldBoundaryFinder(options.boundary);
}

void FieldDetector::setConfiguredColour(const ColorClass& configured) {
  has_configured_ = configured.space == ColorSpace::YUV;
  configured_ = configured;
}

FieldColor FieldDetector::seed() {
  if (has_configured_) {
    const cv::Mat band = columns_.rowRange(model_.bandStart(columns_.rows), columns_.rows);
    const double share = cv::countNonZero(FieldColorModel::mask(band, configured_)) / static_cast<double>(band.total());
    if (share >= model_.options().min_share) {
      FieldColor configured;
      configured.found = true;
      configured.range = configured_;
      configured.share = share;
      return configured;
    }
  }
  return model_.seed(columns_);
}

void FieldDetector::detect(const cv::Mat& bgr, FieldResult* result) {
  const auto start = std::chrono::steady_clock::now();
  *result = FieldResult();
  if (bgr.empty() || bgr.type() != CV_8UC3) return;
  // Only the scanned columns are converted and measured: the colour's statistics from a
  // quarter of the pixels are the same, and the scans read nothing else.
  const int step = std::max(1, finder_.options().column_step_px), first = step / 2;
  columns_ = fieldYuvColumns(bgr, first, step);
  if (columns_.cols == 0) return;
  if (colour_.found) {
    // The light moved too far, or the robot no longer stands on this floor: seed again.
    const cv::Mat band = columns_.rowRange(model_.bandStart(columns_.rows), columns_.rows);
    mask_ = FieldColorModel::mask(band, colour_.range);
    if (cv::countNonZero(mask_) < model_.options().min_share * band.total()) colour_ = FieldColor();
  }
  if (!colour_.found) {
    colour_ = seed();
    result->reseeded = true;
  }
  result->colour = colour_;
  if (colour_.found) {
    result->boundary = finder_.findInColumns(columns_, colour_.range, first, step);
    if (result->boundary.found) {
      // This frame's field: below the boundary (a margin clear of it), for the next frame's range.
      below_.create(columns_.size(), CV_8UC1);
      below_ = cv::Scalar(0);
      for (int j = 0; j < below_.cols; ++j) {
        const int top = std::max(0, static_cast<int>(std::ceil(result->boundary.rowAt(first + j * step))) + 2);
        if (top < below_.rows) below_(cv::Range(top, below_.rows), cv::Range(j, j + 1)) = 255;
      }
      colour_ = model_.update(colour_, columns_, below_);
    }
  }
  result->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rle_vision
