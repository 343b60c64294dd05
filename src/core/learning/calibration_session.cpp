#include "rle_vision/learning/calibration_session.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "rle_vision/color/classifier.h"

namespace rle_vision {

CalibrationSession::CalibrationSession(std::string class_name, CalibrationOptions options)
    : class_name_(std::move(class_name)), options_(options) {
  if (!isPortableClassName(class_name_)) {
    throw std::invalid_argument("class name '" + class_name_ +
                                "': use letters, digits, '_' and '-' (it goes into colors.yaml and colors.txt)");
  }
}

int CalibrationSession::addFrame(const cv::Mat& bgr, const std::string& name) {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw std::invalid_argument(name + ": calibration needs a non-empty 8-bit, 3-channel BGR image");
  }
  CalibrationExample e;
  e.name = name;
  e.bgr = bgr;
  examples_.push_back(std::move(e));
  return frameCount() - 1;
}

void CalibrationSession::addExamples(const std::vector<CalibrationExample>& examples) {
  for (const CalibrationExample& e : examples) checkCalibrationExample(e);
  for (const CalibrationExample& e : examples) {
    examples_.push_back(e);
    for (size_t i = 0; i < e.boxes.size(); ++i) history_.push_back(frameCount() - 1);
  }
  remeasure();
}

cv::Rect CalibrationSession::usableBox(const cv::Rect& box, const cv::Mat& frame) {
  const cv::Rect clipped = box & cv::Rect(0, 0, frame.cols, frame.rows);
  return clipped.width < 2 || clipped.height < 2 ? cv::Rect() : clipped;
}

int CalibrationSession::addFrameWithBox(const cv::Mat& bgr, const std::string& name, const cv::Rect& box) {
  if (usableBox(box, bgr).empty()) return -1;
  const int index = addFrame(bgr, name);
  addBox(index, box);
  return index;
}

bool CalibrationSession::addBox(int frame_index, const cv::Rect& box) {
  CalibrationExample& e = examples_.at(frame_index);
  const cv::Rect clipped = usableBox(box, e.bgr);
  if (clipped.empty()) return false;
  e.boxes.push_back(clipped);
  history_.push_back(frame_index);
  remeasure();
  return true;
}

bool CalibrationSession::undo() {
  if (history_.empty()) return false;
  examples_[history_.back()].boxes.pop_back();
  history_.pop_back();
  remeasure();
  return true;
}

void CalibrationSession::setSpace(ColorSpace space) {
  if (space == options_.space) return;
  options_.space = space;
  remeasure();
}

void CalibrationSession::cycleSpace() {
  setSpace(static_cast<ColorSpace>((static_cast<int>(options_.space) + 1) % kNumColorSpaces));
}

void CalibrationSession::remeasure() {
  ++revision_;
  result_.reset();
  error_.clear();
  if (history_.empty()) return;
  try {
    result_ = calibrateColorClass(examples_, class_name_, options_);
  } catch (const std::invalid_argument& e) {
    error_ = e.what();
  }
}

cv::Mat CalibrationSession::classMask(const cv::Mat& bgr) const {
  if (!result_ || bgr.empty()) return cv::Mat::zeros(bgr.size(), CV_8UC1);
  return colorClassMask(result_->color_class, bgr);
}

MaskCounts CalibrationSession::countMask(const cv::Mat& mask, const std::vector<cv::Rect>& boxes) {
  cv::Mat in_boxes = cv::Mat::zeros(mask.size(), CV_8UC1);
  for (const cv::Rect& b : boxes) in_boxes(b & cv::Rect(0, 0, mask.cols, mask.rows)).setTo(255);
  MaskCounts counts;
  counts.box_area_px = cv::countNonZero(in_boxes);
  cv::Mat inside;
  cv::bitwise_and(mask, in_boxes, inside);
  counts.in_boxes_px = cv::countNonZero(inside);
  counts.outside_px = cv::countNonZero(mask) - counts.in_boxes_px;
  return counts;
}

}  // namespace rle_vision
