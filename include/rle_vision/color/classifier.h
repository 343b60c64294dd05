// Per-pixel colour classification of image rows.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_table.h"
#include "rle_vision/color/pixel_format.h"

namespace rle_vision {
struct YuvBoxes;
}

namespace rle_vision {

// Labels pixels with 1 + the index of the first class containing them (0: no class).
// The result equals ColorTable::mask()/firstClassLabel() pixel by pixel; it is computed with
// one range compare per class and channel on whole rows (vectorised), which is what the
// per-channel bit tables encode for box-shaped classes. Holds row scratch buffers: use one
// instance per thread.
class PixelClassifier {
 public:
  // `src` points at one row of `width` pixels in `format`; `labels` receives `width` bytes.
  void classifyRow(const uint8_t* src, int width, PixelFormat format, const ColorTable& table,
                   uint8_t* labels);
  // Whole image (checked with checkImage(); throws std::invalid_argument) to a CV_8UC1 label image.
  cv::Mat classify(const cv::Mat& image, PixelFormat format, const ColorTable& table);
  // On BGR/RGB rows, YUV classes see each pixel pair's (0-1, 2-3, ...) mean chroma,
  // (a + b + 1) / 2 for U and V, as a 4:2:2 camera sends it; Y stays per pixel. Off by default.
  void setBgrPairChroma(bool on) { bgr_pair_chroma_ = on; }

 private:
  void ensureWidth(int width);
  // Fills the planes of every colour space `table` uses from a BGR/RGB row.
  void planesFromRgbRow(const uint8_t* src, int width, bool src_is_rgb, const ColorTable& table,
                        bool with_yuv);

  // The fused AVX2 kernel's view of the current table (all classes YUV), rebuilt on change.
  const YuvBoxes* yuvBoxesFor(const ColorTable& table);
  std::shared_ptr<YuvBoxes> yuv_boxes_;
  uint64_t yuv_boxes_serial_ = 0;

  bool bgr_pair_chroma_ = false;
  int width_ = 0;
  std::vector<uint8_t> planes_[kNumColorSpaces][3];
  std::vector<uint8_t> scratch_;      // interleaved HSV row
  std::vector<uint8_t> bgr_scratch_;  // 4:2:2 row converted to BGR for RGB/HSV classes
};

// The pixels of a CV_8UC3 BGR image that class `c` takes (CV_8UC1, 255 in the class), as the
// tracker's classifier labels them.
cv::Mat colorClassMask(const ColorClass& c, const cv::Mat& bgr);

}  // namespace rle_vision
