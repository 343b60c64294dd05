// Colour segmentation of one image: classify, run-length encode, group runs into regions.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/classifier.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/color/pixel_format.h"
#include "rle_vision/segment/regions.h"
#include "rle_vision/segment/run_length.h"

namespace rle_vision {

// connectivity, min_area_px (a floor applied to every class on top of its own min_area_px),
// bgr_pair_chroma and flip_filter_px: the SEGMENTER group of tracker_params.def, with their defaults and meanings.
struct SegmenterOptions {
#define RLE_SEGMENTER_PARAM(key, member, type, default_value, min, max, description) \
  type member = static_cast<type>(default_value);
#include "rle_vision/params/tracker_params.def"
};

// Holds all per-frame buffers, sized from the image and reused: no fixed caps, no per-frame
// allocation once warm. Not thread-safe: one instance per thread; the ColorTable is shared.
class Segmenter {
 public:
  explicit Segmenter(const SegmenterOptions& options = SegmenterOptions()) : options_(options) {}
  void setOptions(const SegmenterOptions& options) { options_ = options; }
  const SegmenterOptions& options() const { return options_; }

  // Throws std::invalid_argument with a readable reason when the image does not fit `format`.
  void segment(const cv::Mat& image, PixelFormat format, const ColorTable& table,
               std::vector<Region>* regions);

  // Runs of the last segmented frame; each run's parent is its region's root run.
  const std::vector<Run>& runs() const { return runs_; }
  // The last frame's regions per label (index = label = 1 + class index), of any size: the
  // min areas drop regions from the output, not from these counts.
  const std::vector<uint32_t>& regionCounts() const { return builder_.regionCounts(); }

 private:
  SegmenterOptions options_;
  PixelClassifier classifier_;
  RegionBuilder builder_;
  RowRunEncoder row_encoder_;
  std::vector<uint8_t> labels_;
  std::vector<Run> runs_;
  std::vector<int32_t> row_starts_;
  std::vector<uint32_t> min_area_by_label_;
};

}  // namespace rle_vision
