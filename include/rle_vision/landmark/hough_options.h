// The randomized Hough transform's options, apart from the transform (rle_hough.h) so that its
// private parts (the accumulator) read them without including the transform itself.
#pragma once

#include <cstdint>

namespace rle_vision {

// The parameters (min_votes, min_line_length_px, sampling_margin, ...) are the HOUGH group of
// landmark_params.def, with their defaults and meanings.
struct HoughOptions {
#define RLE_HOUGH_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
  double edge_width_px = 1.5;     // edge pixels per pixel of line length (thinned ridge)
  int max_lines_per_object = 32;
};

}  // namespace rle_vision
