// Least-squares line fitting over runs: sums of pixel coordinates accumulated in closed form
// per run, so fitting a line to an edge object costs O(runs), not O(pixels).
#pragma once

#include <cstdint>

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
  // Pixels x0..x1 (inclusive) of row y, in closed form (inline: the Hough's band scans add
  // every unclaimed stretch through it). Integer sums: exact, as pixel by pixel.
  void addRun(int x0, int x1, int y) {
    const int64_t count = x1 - x0 + 1;
    const int64_t sum_x = (static_cast<int64_t>(x0) + x1) * count / 2;
    // Sum of x^2 for x = x0..x1.
    const auto squares = [](int64_t k) { return k * (k + 1) * (2 * k + 1) / 6; };
    n += static_cast<double>(count);
    sx += static_cast<double>(sum_x);
    sy += static_cast<double>(count * y);
    sxx += static_cast<double>(squares(x1) - squares(x0 - 1));
    sxy += static_cast<double>(sum_x * y);
    syy += static_cast<double>(count * y * y);
  }
  void add(const PointSums& other);

  // Total least squares (principal axis) line through the points. `rms` receives the rms
  // perpendicular distance. False with fewer than 2 points.
  bool fitLine(ImageLine* line, double* rms = nullptr) const;
};

// The pixels x in [x0, x1] of row y whose centre lies within `distance` of the line
// a*x + b*y + c = 0 (a^2 + b^2 = 1): the interval [*lo, *hi]; false when empty.
bool runWithinBand(int x0, int x1, int y, double a, double b, double c, double distance, int* lo, int* hi);

}  // namespace rle_vision
