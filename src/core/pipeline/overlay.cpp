#include "rle_vision/pipeline/overlay.h"

#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_convert.h"

namespace rle_vision {

namespace {
cv::Scalar displayBgr(const ColorClass& c) {
  return cv::Scalar(c.display_rgb[2], c.display_rgb[1], c.display_rgb[0]);
}

// The colour at the centre of a class's box (wrapped ranges included), as BGR.
cv::Scalar rangeCentreBgr(const ColorClass& c) {
  cv::Mat pixel(1, 1, CV_8UC3);
  for (int ch = 0; ch < 3; ++ch) {
    const int span = static_cast<uint8_t>(c.max[ch] - c.min[ch]);
    pixel.at<cv::Vec3b>(0, 0)[ch] = static_cast<uint8_t>((c.min[ch] + span / 2) % (c.space == ColorSpace::HSV && ch == 0 ? 180 : 256));
  }
  cv::Mat bgr;
  switch (c.space) {
    case ColorSpace::YUV: cv::cvtColor(pixel, bgr, cv::COLOR_YUV2BGR); break;
    case ColorSpace::RGB: cv::cvtColor(pixel, bgr, cv::COLOR_RGB2BGR); break;
    case ColorSpace::HSV: cv::cvtColor(pixel, bgr, cv::COLOR_HSV2BGR); break;
  }
  const cv::Vec3b v = bgr.at<cv::Vec3b>(0, 0);
  return cv::Scalar(v[0], v[1], v[2]);
}
}  // namespace

void toDisplayBgr(const cv::Mat& image, PixelFormat format, cv::Mat* bgr) {
  switch (format) {
    case PixelFormat::BGR8: image.copyTo(*bgr); break;
    case PixelFormat::RGB8: cv::cvtColor(image, *bgr, cv::COLOR_RGB2BGR); break;
    case PixelFormat::MONO8: cv::cvtColor(image, *bgr, cv::COLOR_GRAY2BGR); break;
    // A camera's 4:2:2 is video-range YUV, which OpenCV's decode shows as the camera meant it.
    case PixelFormat::UYVY: cv::cvtColor(image, *bgr, cv::COLOR_YUV2BGR_UYVY); break;
    case PixelFormat::YUYV: cv::cvtColor(image, *bgr, cv::COLOR_YUV2BGR_YUY2); break;
  }
}

cv::Mat toDisplayBgr(const cv::Mat& image, PixelFormat format) {
  cv::Mat bgr;
  toDisplayBgr(image, format, &bgr);
  return bgr;
}

void drawBlobs(cv::Mat* canvas, const std::vector<TrackedBlob>& blobs, const ColorTable& table) {
  for (const TrackedBlob& b : blobs) {
    const Region& r = b.region;
    if (r.label < 1 || r.label > table.size()) continue;
    const ColorClass& c = table.classes()[r.label - 1];
    const cv::Scalar colour = displayBgr(c);
    cv::rectangle(*canvas, cv::Rect(cv::Point(r.left, r.top), cv::Point(r.right + 1, r.bottom + 1)), colour, 2);
    cv::drawMarker(*canvas, cv::Point(cvRound(r.cx), cvRound(r.cy)), colour, cv::MARKER_CROSS, 8, 1);
    cv::putText(*canvas, std::to_string(b.id) + " " + c.name, cv::Point(r.left, std::max(10, r.top - 4)),
                cv::FONT_HERSHEY_SIMPLEX, 0.4, colour, 1, cv::LINE_AA);
  }
}

void drawColorSwatches(cv::Mat* canvas, const ColorTable& table) {
  const int size = 18;
  int x = 4;
  const int y = canvas->rows - size - 4;
  for (const ColorClass& c : table.classes()) {
    // Left half: the class's display colour; right half: the colour its range is centred on
    // (watch it follow the light as learned ranges arrive).
    const cv::Rect swatch(x, y, size, size);
    cv::rectangle(*canvas, cv::Rect(x, y, size / 2, size), displayBgr(c), cv::FILLED);
    cv::rectangle(*canvas, cv::Rect(x + size / 2, y, size - size / 2, size), rangeCentreBgr(c), cv::FILLED);
    cv::rectangle(*canvas, swatch, cv::Scalar(255, 255, 255), 1);
    cv::putText(*canvas, c.name + (c.source == "learned" ? "*" : ""), cv::Point(x + size + 3, y + size - 5),
                cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    x += size + 8 + 8 * static_cast<int>(c.name.size() + 1);
  }
}

void drawLearning(cv::Mat* canvas, const std::vector<ColorLearner::Measurement>& measurements) {
  for (const ColorLearner::Measurement& m : measurements) {
    std::vector<cv::Point> polygon;
    for (const cv::Point2d& p : m.region) polygon.emplace_back(cvRound(p.x), cvRound(p.y));
    if (polygon.size() < 3) continue;
    const bool applied = m.rejected.empty();
    // Applied: white (a blob: cyan); refused: red (a blob: orange).
    const cv::Scalar colour = applied ? (m.from_blob ? cv::Scalar(255, 255, 0) : cv::Scalar(255, 255, 255))
                                      : (m.from_blob ? cv::Scalar(0, 128, 255) : cv::Scalar(0, 0, 255));
    if (applied) cv::polylines(*canvas, polygon, true, colour, 1, cv::LINE_AA);
    if (m.pixels_box.empty()) continue;
    cv::rectangle(*canvas, m.pixels_box, colour, 1);
    if (!applied) {
      cv::putText(*canvas, m.rejected, m.pixels_box.tl() + cv::Point(2, 11), cv::FONT_HERSHEY_PLAIN, 0.8, colour, 1,
                  cv::LINE_AA);
    }
  }
}

void drawLandmarks(cv::Mat* canvas, const std::vector<DetectedLine>& lines, const HorizonEstimate& horizon,
                   double roll, double pitch) {
  for (const DetectedLine& l : lines) {
    cv::line(*canvas, cv::Point2d(l.x1, l.y1), cv::Point2d(l.x2, l.y2), cv::Scalar(0, 255, 0), 1, cv::LINE_AA);
  }
  if (!horizon.found) {
    cv::putText(*canvas, "no horizon", cv::Point(6, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 200, 255), 1, cv::LINE_AA);
    return;
  }
  cv::line(*canvas, cv::Point2d(horizon.x1, horizon.y1), cv::Point2d(horizon.x2, horizon.y2), cv::Scalar(255, 255, 0), 2,
           cv::LINE_AA);
  char text[96];
  std::snprintf(text, sizeof(text), "horizon: roll %.1f deg, pitch %s, confidence %.2f", roll * 180 / M_PI,
                std::isfinite(pitch) ? cv::format("%.1f deg", pitch * 180 / M_PI).c_str() : "n/a", horizon.confidence);
  cv::putText(*canvas, text, cv::Point(6, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 0), 1, cv::LINE_AA);
}

void drawFieldBoundary(cv::Mat* canvas, const FieldBoundaryEstimate& boundary) {
  const cv::Scalar orange(0, 140, 255);
  if (!boundary.found) {
    cv::putText(*canvas, "no field boundary", cv::Point(6, 34), cv::FONT_HERSHEY_SIMPLEX, 0.45, orange, 1, cv::LINE_AA);
    return;
  }
  for (size_t i = 1; i < boundary.polyline.size(); ++i) {
    cv::line(*canvas, boundary.polyline[i - 1], boundary.polyline[i], orange, 2, cv::LINE_AA);
  }
  cv::putText(*canvas, cv::format("field boundary: confidence %.2f", boundary.confidence), cv::Point(6, 34),
              cv::FONT_HERSHEY_SIMPLEX, 0.45, orange, 1, cv::LINE_AA);
}

}  // namespace rle_vision
