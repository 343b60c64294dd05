#include "rle_vision/landmark_detector.h"

#include <chrono>
#include <cmath>
#include <limits>

namespace rle_vision {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

bool positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

std::string validateLandmarkOptions(const LandmarkOptions& o) {
  const HoughOptions& h = o.hough;
  const HorizonOptions& z = o.horizon;
  if (!positive(o.edge_gain)) return "edge_gain must be a finite number > 0";
  if (o.objects.gray_threshold == 0) return "gray_threshold must be >= 1";
  if (o.objects.sharp_threshold < o.objects.gray_threshold) return "sharp_threshold must be >= gray_threshold";
  if (h.min_votes < 1) return "min_votes must be >= 1";
  for (double v : {h.min_line_length_px, h.edge_width_px, h.sampling_margin, h.theta_bin_deg, h.intercept_bin_px,
                   h.peak_angle_deg, h.peak_distance_px, h.fit_distance_px, h.max_gap_px}) {
    if (!positive(v)) return "Hough lengths, widths, bins and tolerances must be finite numbers > 0";
  }
  if (!std::isfinite(h.min_pair_distance_px) || h.min_pair_distance_px < 0) return "min_pair_distance_px must be >= 0";
  if (!std::isfinite(h.min_support_ratio) || h.min_support_ratio < 0) return "min_support_ratio must be >= 0";
  if (h.theta_bin_deg > 45) return "theta_bin_deg must be <= 45";
  if (h.max_samples_per_object < 1 || h.max_lines_per_object < 1 || h.max_rounds < 1 || h.max_failed_peaks < 1) {
    return "sample, line, round and failed-peak limits must be >= 1";
  }
  for (double v : {z.min_piece_length_px, z.max_angle_deg, z.merge_angle_deg, z.merge_distance_px}) {
    if (!positive(v)) return "horizon lengths, angles and distances must be finite numbers > 0";
  }
  if (!std::isfinite(z.min_coverage) || z.min_coverage < 0 || z.min_coverage > 1) return "horizon min_coverage must be in [0, 1]";
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
  hough_.detect(finder_, edges.cols, edges.rows, options.hough, &result->lines, &result->hough, &edges,
                options.objects.gray_threshold);
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
