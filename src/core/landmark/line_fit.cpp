#include "rle_vision/landmark/line_fit.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {

void PointSums::add(const PointSums& o) {
  n += o.n;
  sx += o.sx;
  sy += o.sy;
  sxx += o.sxx;
  sxy += o.sxy;
  syy += o.syy;
}

bool PointSums::fitLine(ImageLine* line, double* rms) const {
  if (n < 2) return false;
  const double mx = sx / n, my = sy / n;
  const double cxx = sxx / n - mx * mx, cyy = syy / n - my * my, cxy = sxy / n - mx * my;
  const double theta = 0.5 * std::atan2(2 * cxy, cxx - cyy);  // the major axis
  *line = lineThroughPointWithAngle(mx, my, theta);
  if (rms) {
    // The smaller eigenvalue of the covariance is the mean squared perpendicular distance.
    const double half_trace = 0.5 * (cxx + cyy);
    const double root = std::sqrt(std::max(0.0, 0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy));
    *rms = std::sqrt(std::max(0.0, half_trace - root));
  }
  return true;
}

bool runWithinBand(int x0, int x1, int y, double a, double b, double c, double distance, int* lo, int* hi) {
  const double offset = b * y + c;  // the signed distance is a*x + offset
  double from = x0, to = x1;
  if (std::fabs(a) < 1e-12) {
    if (std::fabs(offset) > distance) return false;
  } else {
    double e0 = (-distance - offset) / a, e1 = (distance - offset) / a;
    if (e0 > e1) std::swap(e0, e1);
    from = std::max(from, std::ceil(e0 - 1e-9));
    to = std::min(to, std::floor(e1 + 1e-9));
  }
  if (from > to) return false;
  *lo = static_cast<int>(from);
  *hi = static_cast<int>(to);
  return true;
}

}  // namespace rle_vision
