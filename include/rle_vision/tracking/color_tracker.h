// The Tracker's work on one frame, without ROS: segment the image with a colour table, then
// track the regions. Regions under the tracking size are counted by the segmenter, but no
// region record is made for them (their runs are still joined and summed), so a noisy frame
// with thousands of specks stays cheap. The Tracker nodelet, the offline CameraStream and
// rle_vision_detect and the benchmarks all run this.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/color/pixel_format.h"
#include "rle_vision/segment/segmenter.h"

namespace rle_vision {

class ColorTracker {
 public:
  explicit ColorTracker(const SegmenterOptions& segmenting = SegmenterOptions(),
                        const TrackerOptions& tracking = TrackerOptions()) {
    setOptions(segmenting, tracking);
  }
  void setOptions(const SegmenterOptions& segmenting, const TrackerOptions& tracking);
  // Throws std::invalid_argument with a readable reason when the image does not fit `format`.
  void process(const cv::Mat& image, PixelFormat format, const ColorTable& table, double stamp_s,
               std::vector<TrackedBlob>* blobs);

  // The last frame's regions per label (1 + class index), of any size.
  const std::vector<uint32_t>& regionCounts() const { return segmenter_.regionCounts(); }
  const BlobTracker& tracker() const { return tracker_; }
  // The regions made: those of tracking size. The blobs are these, in order, unless a class
  // had more than max_regions_per_class (then only its largest are blobs).
  const std::vector<Region>& regions() const { return regions_; }

 private:
  Segmenter segmenter_;
  BlobTracker tracker_;
  std::vector<Region> regions_;
};

}  // namespace rle_vision
