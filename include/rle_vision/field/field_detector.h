// The field stage per frame: the field colour (seeded from the bottom of the view on the first
// frame, then re-measured below the boundary and blended in, re-seeded when it no longer
// covers the bottom of the view) and the field boundary it gives.
#pragma once

#include <opencv2/core.hpp>

#include "rle_vision/field/field_boundary.h"
#include "rle_vision/field/field_color.h"

namespace rle_vision {

struct FieldResult {
  FieldColor colour;        // the range used on this frame (and its share of the floor)
  FieldBoundaryEstimate boundary;
  bool reseeded = false;    // the colour was seeded on this frame
  double ms = 0;            // time of the stage
};

// Holds the colour across frames and the buffers; one instance per camera stream and thread.
class FieldDetector {
 public:
  explicit FieldDetector(const FieldColorOptions& colour = FieldColorOptions(),
                         const FieldBoundaryOptions& boundary = FieldBoundaryOptions())
      : model_(colour), finder_(boundary) {}

  // One BGR frame (CV_8UC3); an empty or other image gives no boundary.
  void detect(const cv::Mat& bgr, FieldResult* result);
  // Forget the colour: the next frame seeds it again.
  void reset() { colour_ = FieldColor(); }

 private:
  FieldColorModel model_;
  FieldBoundaryFinder finder_;
  FieldColor colour_;
  cv::Mat columns_, mask_, below_;  // the scanned columns' YUV, their bottom band's field mask, this frame's field
};

}  // namespace rle_vision
