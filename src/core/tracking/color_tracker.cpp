#include "rle_vision/tracking/color_tracker.h"

#include <algorithm>

namespace rle_vision {

void ColorTracker::setOptions(const SegmenterOptions& segmenting, const TrackerOptions& tracking) {
  SegmenterOptions floored = segmenting;
  floored.min_area_px = std::max(segmenting.min_area_px, tracking.limits.min_track_area_px);
  segmenter_.setOptions(floored);
  tracker_.setOptions(tracking);
}

void ColorTracker::process(const cv::Mat& image, PixelFormat format, const ColorTable& table, double stamp_s,
                           std::vector<TrackedBlob>* blobs) {
  segmenter_.segment(image, format, table, &regions_);
  tracker_.update(regions_, stamp_s, blobs);
}

}  // namespace rle_vision
