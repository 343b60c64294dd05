#include "rle_vision/learning/calibration_view.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <opencv2/imgproc.hpp>

namespace rle_vision {
namespace {

const int kFont = cv::FONT_HERSHEY_SIMPLEX;
const double kFontScale = 0.45;
const int kLineHeightPx = 18;

// `text` broken at spaces into lines no wider than `width_px` (a word wider than that gets a
// line of its own).
std::vector<std::string> wrapped(const std::string& text, int width_px) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    const std::string longer = line.empty() ? word : line + " " + word;
    int baseline = 0;
    if (!line.empty() && cv::getTextSize(longer, kFont, kFontScale, 1, &baseline).width > width_px) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string rangeText(const ColorClass& c) {
  char text[96];
  std::snprintf(text, sizeof(text), "[%d %d %d]..[%d %d %d]", c.min[0], c.min[1], c.min[2], c.max[0], c.max[1],
                c.max[2]);
  return text;
}

}  // namespace

cv::Mat renderCalibrationView(const CalibrationView& view) {
  const int margin_px = 6, width = view.bgr.cols;
  std::vector<std::string> lines;
  for (const std::string& s : view.status) {
    for (const std::string& l : wrapped(s, width - 2 * margin_px)) lines.push_back(l);
  }
  const size_t status_lines = lines.size();
  for (const std::string& l : wrapped(view.help, width - 2 * margin_px)) lines.push_back(l);
  const int band_px = static_cast<int>(lines.size()) * kLineHeightPx + margin_px;
  cv::Mat picture(view.bgr.rows + band_px, width, CV_8UC3, cv::Scalar(32, 32, 32));
  cv::Mat frame = picture(cv::Rect(0, 0, width, view.bgr.rows));
  view.bgr.copyTo(frame);
  if (!view.mask.empty()) {
    cv::Mat tinted;
    cv::addWeighted(view.bgr, 0.4, cv::Mat(view.bgr.size(), CV_8UC3, kCalibrationMaskTint), 0.6, 0, tinted);
    tinted.copyTo(frame, view.mask);
  }
  for (const cv::Rect& b : view.boxes) cv::rectangle(frame, b, cv::Scalar(0, 255, 0), 1);
  if (!view.dragging.empty()) cv::rectangle(frame, view.dragging, cv::Scalar(0, 255, 255), 1);
  for (size_t i = 0; i < lines.size(); ++i) {
    const cv::Scalar colour = i < status_lines ? cv::Scalar(255, 255, 255) : cv::Scalar(170, 200, 170);
    cv::putText(picture, lines[i], cv::Point(margin_px, view.bgr.rows + static_cast<int>(i + 1) * kLineHeightPx - 4),
                kFont, kFontScale, colour, 1, cv::LINE_AA);
  }
  return picture;
}

std::vector<std::string> calibrationStatus(const CalibrationSession& session, const MaskCounts& counts) {
  std::vector<std::string> status;
  const std::string head = session.className() + " (" + toString(session.space()) + ")";
  const auto& result = session.result();
  if (result) {
    status.push_back(head + " " + rangeText(result->color_class) + ", " + std::to_string(session.boxCount()) +
                     " boxes (" + std::to_string(result->boxes_dropped) + " dropped)");
  } else if (!session.lastError().empty()) {
    status.push_back(head + ": no class: " + session.lastError());
  } else {
    status.push_back(head + ": drag a box around the object");
  }
  char counts_text[128];
  const double share = counts.box_area_px > 0 ? 100.0 * counts.in_boxes_px / counts.box_area_px : 0.0;
  std::snprintf(counts_text, sizeof(counts_text), "mask: %d px in the boxes (%.0f%% of them), %d px outside",
                counts.in_boxes_px, share, counts.outside_px);
  status.push_back(counts_text);
  return status;
}

}  // namespace rle_vision
