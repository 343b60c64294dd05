#include "rle_vision/landmark_detector.h"

#include <chrono>
#include <cmath>
#include <limits>

#include "param_range.h"

namespace rle_vision {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
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
#include "rle_vision/landmark_params.def"
#undef RLE_CHECK
  if (!problem.empty()) return problem;
  if (o.objects.sharp_threshold < o.objects.gray_threshold) return "sharp_threshold must be >= gray_threshold";
  if (!(std::isfinite(o.hough.edge_width_px) && o.hough.edge_width_px > 0)) return "edge_width_px must be a finite number > 0";
  if (o.hough.max_lines_per_object < 1) return "max_lines_per_object must be >= 1";
  return "";
}

void LandmarkDetector::detectInImage(const cv::Mat& image, const LandmarkOptions& options, LandmarkResult* result) {
  const auto start = std::chrono::steady_clock::now();
  sobel_.edges(image, options.edge_gain, &edges_);
  const double sobel_ms = msSince(start);
  detectInEdges(edges_, options, result);
  result->sobel_ms = sobel_ms;
}

void LandmarkDetector::detectInEdges(const cv::Mat& edges, const LandmarkOptions& options, LandmarkResult* result) {
  result->sobel_ms = 0;
  auto start = std::chrono::steady_clock::now();
  finder_.find(edges, options.objects);
  result->objects_ms = msSince(start);
  result->edge_objects = finder_.objects().size();
  result->edge_pixels = finder_.edgePixels();
  result->edge_runs = finder_.runCount();
  start = std::chrono::steady_clock::now();
  hough_.detect(finder_, edges, options.objects.gray_threshold, options.hough, &result->lines, &result->hough);
  result->hough_ms = msSince(start);
  start = std::chrono::steady_clock::now();
  result->horizon = findHorizon(result->lines, edges.cols, edges.rows, options.horizon);
  result->horizon_ms = msSince(start);
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
