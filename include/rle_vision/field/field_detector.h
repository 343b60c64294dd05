// The field stage per frame: the field colour (seeded from the bottom of the view on the first
// frame, then re-measured below the boundary and blended in, re-seeded when it no longer
// covers the bottom of the view) and the field boundary it gives.
#pragma once

#include <string>

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

// The field stage's parameters (the FIELD_COLOR and FIELD_BOUNDARY groups of landmark_params.def).
struct FieldOptions {
  FieldColorOptions colour;
  FieldBoundaryOptions boundary;
};

// Empty when every parameter lies within the table's limits, else the first problem.
std::string validateFieldOptions(const FieldOptions& options);

// Holds the colour across frames and the buffers; one instance per camera stream and thread.
class FieldDetector {
 public:
  explicit FieldDetector(const FieldOptions& options = FieldOptions())
      : model_(options.colour), finder_(options.boundary) {}

  // One BGR frame (CV_8UC3); an empty or other image gives no boundary.
  void detect(const cv::Mat& bgr, FieldResult* result);
  // Forget the colour: the next frame seeds it again.
  void reset() { colour_ = FieldColor(); }
  // New parameters (validated by the caller); the colour followed so far is kept.
  void setOptions(const FieldOptions& options);
  // A configured floor colour (a YUV class, e.g. the colours file's `field`): a seed takes it
  // when it covers min_share of the bottom band, and the band's own dominant colour otherwise
  // (the light moved, or the file is for another hall). Other colour spaces are ignored.
  void setConfiguredColour(const ColorClass& configured);

 private:
  FieldColor seed();

  FieldColorModel model_;
  FieldBoundaryFinder finder_;
  FieldColor colour_;
  ColorClass configured_;
  bool has_configured_ = false;
  cv::Mat columns_, mask_, below_;  // the scanned columns' YUV, their bottom band's field mask, this frame's field
};

}  // namespace rle_vision
