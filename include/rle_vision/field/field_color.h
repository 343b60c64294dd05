// The floor's colour, found and kept by the package itself: the paper's colour-update loop
// applied to the largest object in view. Seeded from the dominant colour at the bottom of the
// view (where a robot's camera sees the floor it stands on), then re-measured on each frame's
// field and blended in, so that it follows the light.
#pragma once

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"

namespace rle_vision {

// The parameters (field_seed_band_share, field_blend, ...) are the FIELD_COLOR group of
// landmark_params.def, with their defaults and meanings.
struct FieldColorOptions {
#define RLE_FIELD_COLOR_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
};

struct FieldColor {
  bool found = false;
  ColorClass range;   // "field", in YUV (source "learned")
  double share = 0;   // share of the measured pixels inside the range
};

// The YUV (OpenCV COLOR_BGR2YUV) statistics of a pixel set: medians and robust spreads.
struct ChannelStats {
  double median[3] = {0, 0, 0};
  double sigma[3] = {0, 0, 0};  // 1.4826 x median absolute deviation
  size_t pixels = 0;
};

class FieldColorModel {
 public:
  explicit FieldColorModel(const FieldColorOptions& options = FieldColorOptions()) : options_(options) {}

  // The dominant colour of the bottom band of `yuv` (CV_8UC3, YUV): the mode of its chroma
  // histogram, widened to the pixels around it by their robust spread (twice, so the range
  // settles on the mode's own pixels). Not found when the mode covers less than min_share.
  FieldColor seed(const cv::Mat& yuv) const;

  // Re-measures the range on `field_mask` (CV_8UC1, non-zero: this frame's field, e.g. below
  // the field boundary and inside the current range grown by the spread) and blends it in.
  FieldColor update(const FieldColor& current, const cv::Mat& yuv, const cv::Mat& field_mask) const;

  // Pixels of `yuv` inside the range (CV_8UC1, 255 / 0).
  static cv::Mat mask(const cv::Mat& yuv, const ColorClass& range);

  // The first row of the bottom band the colour is seeded from (seed_band_share of `rows`).
  int bandStart(int rows) const;

  const FieldColorOptions& options() const { return options_; }

 private:
  ColorClass rangeFrom(const ChannelStats& stats) const;

  FieldColorOptions options_;
};

// Converts a BGR image (CV_8UC3) to the package's YUV (bit-exact with cv::cvtColor).
cv::Mat fieldYuv(const cv::Mat& bgr);
// The same for image columns first_x, first_x + step_x, ... only (a narrow CV_8UC3 image): what
// the field stage reads of a frame.
cv::Mat fieldYuvColumns(const cv::Mat& bgr, int first_x, int step_x);

}  // namespace rle_vision
