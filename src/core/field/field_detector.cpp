#include "rle_vision/field/field_detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rle_vision {
namespace {

// Share of the bottom band's pixels that `mask` holds.
double bottomShare(const cv::Mat& mask, double band_share) {
  const int row0 = std::min(mask.rows - 1, static_cast<int>(std::floor(mask.rows * (1.0 - band_share))));
  const cv::Mat band = mask.rowRange(row0, mask.rows);
  return static_cast<double>(cv::countNonZero(band)) / band.total();
}

}  // namespace

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
    mask_ = FieldColorModel::mask(columns_, colour_.range);
    if (bottomShare(mask_, model_.options().seed_band_share) < model_.options().min_share) colour_ = FieldColor();
  }
  if (!colour_.found) {
    colour_ = model_.seed(columns_);
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
