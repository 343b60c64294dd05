// Sub-pixel refinement of a line on an edge image: along the line, one point per pixel step
// at the centre of the edge profile across it; a robust total-least-squares fit through those
// points; the stretches where the ridge follows the fitted line, split where they bend.
#pragma once

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/landmark/line_fit.h"
#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {

struct RidgeFitOptions {
  double half_width_px = 4;   // the profile across the line spans +- this
  double min_strength = 60;   // weaker profile maxima are not ridge points
  double inlier_px = 1.5;     // ridge points this close to the fitted line form the segment
  double max_gap_px = 8;      // a longer gap between ridge points ends the segment
  double split_px = 1.0;      // a stretch bending further than this from its chord ...
  double split_angle_deg = 2; // ... into two sides this different in angle is split
  double end_trim_px = 3;     // the final fit leaves out this much at each end (at most 15%)
};

struct RidgeFit {
  ImageLine line;
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // the stretch's end points on the line
  double rms = 0;                         // rms distance of its ridge points, px
  int points = 0;                         // its ridge points
  PointSums sums;                         // its ridge points (for merging lines)
};

// Refines lines on an edge image. Holds scratch buffers; reuse one instance per thread.
class RidgeFitter {
 public:
  // Refines `line` on the CV_8UC1 `edges` between positions t0 and t1 along it (t = x cos
  // theta + y sin theta): the straight stretches of ridge along it at least `min_length` long.
  void fit(const cv::Mat& edges, const ImageLine& line, double t0, double t1, const RidgeFitOptions& options,
           double min_length, std::vector<RidgeFit>* fits);

 private:
  struct RidgePoint {
    double x, y, t;
  };
  void ridgePoints(const cv::Mat& edges, const ImageLine& line, double t0, double t1, const RidgeFitOptions& o);
  void fitRobustly(const ImageLine& start, const RidgeFitOptions& o, double min_length, std::vector<RidgeFit>* fits);
  void splitAndFit(size_t first, size_t last, const RidgeFitOptions& o, double min_length, int depth,
                   std::vector<RidgeFit>* fits);

  std::vector<double> profile_, offset_x_, offset_y_;  // a profile and its samples' offsets
  std::vector<RidgePoint> points_, inliers_;
  std::vector<double> residuals_, sorted_, deviation_;
};

}  // namespace rle_vision
