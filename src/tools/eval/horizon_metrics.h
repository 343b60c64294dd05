// Scoring a horizon against a labelled one (make eval): the pass criterion of the targets
// (docs/ARCHITECTURE.md)
// (pass = angle error < 5 deg and Hesse distance error < 5% of the image height).
#pragma once

#include <cmath>
#include <string>

#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {
namespace eval {

constexpr double kPassAngleDeg = 5.0;
constexpr double kPassDistanceShareOfHeight = 0.05;
// A segment lies on the horizon: at least this long, this parallel, its centre this near.
constexpr double kOnHorizonMinLengthPx = 40.0;
constexpr double kOnHorizonAngleDeg = 2.0;
constexpr double kOnHorizonDistanceShareOfHeight = 0.03;

// A labelled frame: the horizon y = slope x + offset * height (pixel coordinates, x right,
// y down), or none.
struct HorizonLabel {
  std::string file;
  bool has_horizon = true;
  double slope = 0, offset = 0;
  ImageLine line(int height) const { return lineThroughPoints(0.0, offset * height, 1.0, slope + offset * height); }
};

// The Hesse normal form's distance of a line from the image centre, the normal oriented
// downwards (towards +y), so that two nearly parallel lines compare as plain numbers.
inline double hesseDistanceFromCentre(const ImageLine& line, int width, int height) {
  double a, b, c;
  homogeneousFromLine(line, &a, &b, &c);  // a x + b y + c = 0, (a, b) a unit normal
  if (b < 0 || (b == 0 && a < 0)) {
    a = -a;
    b = -b;
    c = -c;
  }
  return -(a * 0.5 * (width - 1) + b * 0.5 * (height - 1) + c);
}

struct HorizonError {
  double angle_deg = 0;
  double distance_px = 0;
};

inline HorizonError horizonError(const ImageLine& detected, const ImageLine& truth, int width, int height) {
  HorizonError e;
  e.angle_deg = lineAngleDifference(detected.theta, truth.theta) * 180.0 / M_PI;
  e.distance_px = std::fabs(hesseDistanceFromCentre(detected, width, height) - hesseDistanceFromCentre(truth, width, height));
  return e;
}

inline bool passes(const HorizonError& e, int height) {
  return e.angle_deg < kPassAngleDeg && e.distance_px < kPassDistanceShareOfHeight * height;
}

// A detected segment lies on the true horizon.
inline bool segmentOnHorizon(double x1, double y1, double x2, double y2, const ImageLine& truth, int height) {
  if (std::hypot(x2 - x1, y2 - y1) < kOnHorizonMinLengthPx) return false;
  if (lineAngleDifference(lineThroughPoints(x1, y1, x2, y2).theta, truth.theta) * 180.0 / M_PI >= kOnHorizonAngleDeg) {
    return false;
  }
  return std::fabs(signedDistance(truth, 0.5 * (x1 + x2), 0.5 * (y1 + y2))) < kOnHorizonDistanceShareOfHeight * height;
}

}  // namespace eval
}  // namespace rle_vision
