// Least-squares line fitting over runs: sums of pixel coordinates accumulated in closed form
// per run, so fitting a line to an edge object costs O(runs), not O(pixels).
#pragma once

#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {

// Sums over (optionally weighted) pixels; n is the total weight.
struct PointSums {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;

  // Inline: the Hough's band scans and the ridge fit add every pixel through it.
  void addPixel(double x, double y, double weight = 1.0) {
    n += weight;
    sx += weight * x;
    sy += weight * y;
    sxx += weight * x * x;
    sxy += weight * x * y;
    syy += weight * y * y;
  }
  // Pixels x0..x1 (inclusive) of row y.
  void addRun(int x0, int x1, int y);
  void add(const PointSums& other);

  // Total least squares (principal axis) line through the points. `rms` receives the rms
  // perpendicular distance. False with fewer than 2 points.
  bool fitLine(ImageLine* line, double* rms = nullptr) const;
};

// The pixels x in [x0, x1] of row y whose centre lies within `distance` of the line
// a*x + b*y + c = 0 (a^2 + b^2 = 1): the interval [*lo, *hi]; false when empty.
bool runWithinBand(int x0, int x1, int y, double a, double b, double c, double distance, int* lo, int* hi);

}  // namespace rle_vision
