// What the calibration window shows (no window here, only the picture): the frame with the
// class's mask tinted over it, the boxes, the box being dragged, and below the frame a text
// band (status lines, then the help line, wrapped to the frame's width). The frame keeps its
// pixel coordinates in the picture, so a mouse position on the picture is a frame pixel.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/learning/calibration_session.h"

namespace rle_vision {

struct CalibrationView {
  cv::Mat bgr;                    // the frame (CV_8UC3)
  cv::Mat mask;                   // the class's pixels (CV_8UC1), or empty
  std::vector<cv::Rect> boxes;    // the frame's boxes
  cv::Rect dragging;              // the box being dragged (empty: none)
  std::vector<std::string> status;
  std::string help;
};

// The colour the mask is tinted with (BGR): magenta, rare on fields, balls and robots.
const cv::Scalar kCalibrationMaskTint(255, 0, 255);

cv::Mat renderCalibrationView(const CalibrationView& view);

// The status lines for a session's class on a frame: the class and its range (or why there
// is none), and the mask's pixel counts in and out of the frame's boxes.
std::vector<std::string> calibrationStatus(const CalibrationSession& session, const MaskCounts& counts);

}  // namespace rle_vision
