// The horizon from detected lines: long, not-near-vertical lines from every edge object are
// candidates; collinear candidates (the paper's three horizon pieces) merge into one line,
// refitted on all their pixels; the longest merged line that spans enough of the image wins.
#pragma once

#include <vector>

#include "rle_vision/rle_hough.h"

namespace rle_vision {

struct HorizonOptions {
  double min_piece_length_px = 40;  // shorter lines are not horizon pieces
  double max_angle_deg = 40;        // steeper lines are not horizon pieces
  double merge_angle_deg = 2;       // pieces this parallel ...
  double merge_distance_px = 4;     // ... and this close to each other's line are one line
  double min_coverage = 0.4;        // the merged pieces must cover this share of the line's run across the image
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
