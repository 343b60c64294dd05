#include "rle_vision/landmark/landmark_detector.h"

#include <chrono>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "rle_vision/landmark/param_range.h"

namespace rle_vision {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The horizon found from region evidence and edge points is a line of the frame too: its
// supported segment joins the lines unless a Hough line already is that line (parallel within
// a Hough angle bin, both ends on it, most of its length).
void addHorizonSegment(const HorizonEstimate& h, const LandmarkOptions& o, std::vector<DetectedLine>* lines) {
  const double length = std::hypot(h.x2 - h.x1, h.y2 - h.y1);
  if (!h.found || length < o.hough.min_line_length_px) return;
  for (const DetectedLine& l : *lines) {
    if (l.length >= 0.8 * length && lineAngleDifference(l.line.theta, h.line.theta) <= o.hough.theta_bin_deg * M_PI / 180 &&
        std::fabs(signedDistance(h.line, l.x1, l.y1)) <= o.horizon.inlier_px &&
        std::fabs(signedDistance(h.line, l.x2, l.y2)) <= o.horizon.inlier_px) {
      return;
    }
  }
  DetectedLine d;
  d.line = h.line;
  d.x1 = h.x1;
  d.y1 = h.y1;
  d.x2 = h.x2;
  d.y2 = h.y2;
  d.length = std::hypot(h.x2 - h.x1, h.y2 - h.y1);
  d.support = h.support;  // its edge points; no Hough votes
  d.rms = h.rms;
  lines->push_back(d);
}

}  // namespace

std::string validateLandmarkOptions(const LandmarkOptions& o) {
  std::string problem;
  // Every parameter within the limits landmark_params.def gives it.
#define RLE_CHECK(value, key, min, max) \
  if (problem.empty()) problem = outOfRange(#key, value, min, max);
#define RLE_EDGE_PARAM(key, member, type, default_value, min, max, description) RLE_CHECK(o.member, key, min, max)
#define RLE_OBJECTS_PARAM(key, member, type, default_value, min, max, description) RLE_CHECK(o.objects.member, key, min, max)
#define RLE_HOUGH_PARAM(key, member, type, default_value, min, max, description) RLE_CHECK(o.hough.member, key, min, max)
#define RLE_HORIZON_PARAM(key, member, type, default_value, min, max, description) RLE_CHECK(o.horizon.member, key, min, max)
#include "rle_vision/params/landmark_params.def"
#undef RLE_CHECK
  if (!problem.empty()) return problem;
  if (o.objects.sharp_threshold < o.objects.gray_threshold) return "sharp_threshold must be >= gray_threshold";
  if (o.objects.adaptive && o.objects.min_value > o.objects.gray_threshold) {
    return "edge_min_value must be <= gray_threshold (adaptive_edges lowers the gray band between them)";
  }
  if (!(std::isfinite(o.hough.edge_width_px) && o.hough.edge_width_px > 0)) return "edge_width_px must be a finite number > 0";
  if (o.hough.max_lines_per_object < 1) return "max_lines_per_object must be >= 1";
  return "";
}

void LandmarkDetector::detectInImage(const cv::Mat& image, const LandmarkOptions& options, LandmarkResult* result) {
  const auto start = std::chrono::steady_clock::now();
  sobel_.edges(image, options.edge_gain, &edges_);
  const double sobel_ms = msSince(start);
  if (image.type() == CV_8UC3) {
    detect(image, edges_, options, result);
  } else {
    cv::cvtColor(image, gray_as_bgr_, cv::COLOR_GRAY2BGR);
    detect(gray_as_bgr_, edges_, options, result);
  }
  result->sobel_ms = sobel_ms;
}

void LandmarkDetector::detect(const cv::Mat& bgr, const cv::Mat& edges, const LandmarkOptions& options,
                              LandmarkResult* result) {
  findLines(edges, options, result);
  const auto start = std::chrono::steady_clock::now();
  if (!bgr.empty() && bgr.type() == CV_8UC3 && bgr.size() == edges.size()) {
    result->horizon = horizon_.detect(bgr, edges, options.edge_gain, result->lines, options.horizon);
    addHorizonSegment(result->horizon, options, &result->lines);
  } else {
    result->horizon = HorizonEstimate();
  }
  result->horizon_ms = msSince(start);
}

void LandmarkDetector::detectInEdges(const cv::Mat& edges, const LandmarkOptions& options, LandmarkResult* result) {
  findLines(edges, options, result);
  const auto start = std::chrono::steady_clock::now();
  result->horizon = findHorizon(result->lines, edges.cols, edges.rows, options.horizon);
  result->horizon_ms = msSince(start);
}

void LandmarkDetector::findLines(const cv::Mat& edges, const LandmarkOptions& options, LandmarkResult* result) {
  result->sobel_ms = 0;
  auto start = std::chrono::steady_clock::now();
  finder_.find(edges, options.objects);
  result->objects_ms = msSince(start);
  result->edge_objects = finder_.objects().size();
  result->edge_pixels = finder_.edgePixels();
  result->edge_runs = finder_.runCount();
  start = std::chrono::steady_clock::now();
  hough_.detect(finder_, edges, finder_.grayThreshold(), options.hough, &result->lines, &result->hough);
  result->hough_ms = msSince(start);
}

void horizonAttitude(const ImageLine& horizon, const PinholeCamera* camera, double* roll, double* pitch) {
  if (camera && camera->valid()) {
    attitudeFromHorizon(*camera, horizon, roll, pitch);
    return;
  }
  *roll = -horizon.theta;
  *pitch = std::numeric_limits<double>::quiet_NaN();
}

}  // namespace rle_vision
