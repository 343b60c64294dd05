// The state behind interactive colour calibration (rle_vision_calibrate --gui, calibrate_gui):
// frames with the boxes a user dragged over the object, the class re-measured after every
// change with the command line tool's statistics and background gate (color_calibration.h),
// undo, the class's colour space, and the class's mask with its pixel counts in and out of the
// boxes. No window here: the GUI drives it, the tests drive it the same way.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/learning/color_calibration.h"

namespace rle_vision {

// How a class mask splits over a frame: its pixels inside the union of the frame's boxes
// and outside it, and how many pixels the boxes cover.
struct MaskCounts {
  int in_boxes_px = 0;
  int outside_px = 0;
  int box_area_px = 0;
};

class CalibrationSession {
 public:
  // Throws std::invalid_argument for a name colors.yaml and colors.txt cannot take.
  CalibrationSession(std::string class_name, CalibrationOptions options);

  // A frame to box on (BGR, CV_8UC3, not empty; throws std::invalid_argument otherwise).
  // Frames without boxes still count: their pixels are colours the class must avoid.
  int addFrame(const cv::Mat& bgr, const std::string& name);
  // Frames with boxes given up front (--box, --label-class), the class measured once. Throws
  // std::invalid_argument, naming the frame, for an unusable image or a box outside it.
  void addExamples(const std::vector<CalibrationExample>& examples);
  // A box on a frame not kept yet (a live camera's): the frame is kept only when the box is
  // (see addBox). Its index, or -1 for a click.
  int addFrameWithBox(const cv::Mat& bgr, const std::string& name, const cv::Rect& box);
  int frameCount() const { return static_cast<int>(examples_.size()); }
  const CalibrationExample& frame(int index) const { return examples_.at(index); }

  // Adds a box (clipped to the frame) and re-measures the class. False, with nothing
  // changed, when the clipped box is smaller than 2 x 2 px (a click, not a drag).
  bool addBox(int frame_index, const cv::Rect& box);
  // Removes the most recent box and re-measures. False when there is none.
  bool undo();
  int boxCount() const { return static_cast<int>(history_.size()); }

  void setSpace(ColorSpace space);
  void cycleSpace();  // YUV -> RGB -> HSV -> YUV
  ColorSpace space() const { return options_.space; }
  const std::string& className() const { return class_name_; }

  // The class measured from the boxes so far; empty before the first box, or when the boxes
  // hold no usable object pixels (then lastError() says why).
  const std::optional<CalibrationResult>& result() const { return result_; }
  const std::string& lastError() const { return error_; }

  // Changes whenever the class may have: a mask drawn with an older revision is stale.
  int revision() const { return revision_; }

  // The current class's pixels in `bgr` (CV_8UC1, 255 = in the class); all zero without one.
  cv::Mat classMask(const cv::Mat& bgr) const;
  // The counts of `mask` over the frame's boxes (`boxes` may be empty: all pixels outside).
  static MaskCounts countMask(const cv::Mat& mask, const std::vector<cv::Rect>& boxes);

 private:
  void remeasure();
  // The box clipped to the frame; empty when less than 2 x 2 pixels remain to measure.
  static cv::Rect usableBox(const cv::Rect& box, const cv::Mat& frame);

  std::string class_name_;
  CalibrationOptions options_;
  std::vector<CalibrationExample> examples_;
  std::vector<int> history_;  // the frame of each box, in the order added (for undo)
  std::optional<CalibrationResult> result_;
  std::string error_;
  int revision_ = 0;
};

}  // namespace rle_vision
