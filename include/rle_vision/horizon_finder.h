// The horizon from detected lines: long, not-near-vertical lines from every edge object are
// candidates; collinear candidates (the paper's three horizon pieces) merge into one line,
// refitted on all their pixels; the longest merged line that spans enough of the image wins.
#pragma once

#include <vector>

#include "rle_vision/detected_line.h"

namespace rle_vision {

// The parameters (min_piece_length_px, max_angle_deg, merge_angle_deg, merge_distance_px,
// min_coverage) are the HORIZON group of landmark_params.def, with their defaults and meanings.
struct HorizonOptions {
#define RLE_HORIZON_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/landmark_params.def"
};

struct HorizonEstimate {
  bool found = false;
  ImageLine line;
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // extent of the merged pieces
  double length = 0;       // summed length of the pieces, px
  double coverage = 0;     // length / the line's length inside the image, 0..1
  double rms = 0;          // rms distance of the pieces' pixels from the merged line, px
  double confidence = 0;   // coverage, lowered when the fit is loose (rms above 1.5 px)
  uint32_t votes = 0, support = 0;
  int pieces = 0;
};

HorizonEstimate findHorizon(const std::vector<DetectedLine>& lines, int width, int height,
                            const HorizonOptions& options);

}  // namespace rle_vision
