// A straight line segment found in an image, as the landmark path reports it.
#pragma once

#include <cstdint>

#include "rle_vision/landmark/line_fit.h"
#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {

struct DetectedLine {
  ImageLine line;
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // supported segment
  double length = 0;                      // px
  uint32_t votes = 0;                     // Hough votes of its peak
  uint32_t support = 0;                   // object pixels within 1.5 px of the segment
  double rms = 0;                         // rms distance of the fitted pixels, px
  int object = -1;                        // edge object it comes from
  PointSums sums;                         // the fitted pixels (lets lines be merged and refitted)
};

}  // namespace rle_vision
