// A colour class from examples (what cmvision users did with a GUI colour picker): images with
// boxes around the object; each box trimmed to the object; the class is the paper's statistics
// on what is left, optionally tightened so that the rest of the labelled images stays out.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/learning/color_learning.h"

namespace rle_vision {

struct CalibrationOptions {
  ColorSpace space = ColorSpace::YUV;
  // The paper's statistics (see colorStats).
  double outlier_distance = 40;
  uint32_t large_object_px = 100;
  double small_object_margin = 15;
  // Trimming a box to its object: the surroundings are a ring this fraction of the box's
  // shorter side wide (at least 2 px) around it; box pixels within max(background_radius,
  // 2.5 sigma) of one of the ring's colour modes are background; of the rest, the colour mode
  // that fills the box's centre is the object.
  double ring_fraction = 0.15;
  double background_radius = 12;
  double object_mode_radius = 20;
  // Tighten the statistics' range against the pixels of the labelled images outside every
  // box (the colours the class must not take): each bound moves while the F1 score of
  // "object pixels in, other pixels out" rises.
  bool exclude_background = true;
  uint32_t min_area_px = 20;  // the class's smallest tracked region
};

// One labelled image: BGR (CV_8UC3) and the boxes of the object (each inside the image).
struct CalibrationExample {
  std::string name;  // for error messages
  cv::Mat bgr;
  std::vector<cv::Rect> boxes;
};

struct CalibrationResult {
  ColorClass color_class;     // the class to use (tightened when exclude_background)
  ColorStats stats;           // the paper's statistics on the examples' object pixels
  int boxes_used = 0;         // boxes whose object colour agreed with the others
  int boxes_dropped = 0;      // boxes with no object pixels or a colour far from the others'
  double object_recall = 0;   // mean fraction of each box's object pixels inside the class
  double other_pixels_per_image = 0;  // pixels outside every box that the class takes
};

// The object's pixels in one box of an image already in the class's space (CV_8UC3).
std::vector<Channels> objectPixelsInBox(const cv::Mat& image_in_space, const cv::Rect& box,
                                        const CalibrationOptions& options);

// Throws std::invalid_argument, naming the example, for an empty or non-BGR image, an empty
// box, or a box outside its image.
void checkCalibrationExample(const CalibrationExample& e);

// The class named `name` from `examples`. Throws std::invalid_argument with the example's
// name and the reason for an empty image, a box outside its image or an empty box, and when
// no box holds object pixels.
CalibrationResult calibrateColorClass(const std::vector<CalibrationExample>& examples, const std::string& name,
                                      const CalibrationOptions& options = CalibrationOptions());

}  // namespace rle_vision
