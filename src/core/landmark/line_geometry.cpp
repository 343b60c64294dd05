#include "rle_vision/landmark/line_geometry.h"

#include <algorithm>

namespace rle_vision {

double normalizeLineAngle(double theta) {
  theta = std::fmod(theta, M_PI);
  if (theta <= -M_PI / 2) theta += M_PI;
  if (theta > M_PI / 2) theta -= M_PI;
  return theta;
}

double lineAngleDifference(double theta_a, double theta_b) {
  const double d = std::fabs(normalizeLineAngle(theta_a - theta_b));
  return std::min(d, M_PI - d);
}

double interceptFor(double theta, double x, double y) {
  if (usesYIntercept(theta)) return y - x * std::tan(theta);  // y at x = 0
  return x - y * std::cos(theta) / std::sin(theta);           // x at y = 0
}

ImageLine lineThroughPointWithAngle(double x, double y, double theta) {
  ImageLine line;
  line.theta = normalizeLineAngle(theta);
  line.intercept = interceptFor(line.theta, x, y);
  return line;
}

ImageLine lineThroughPoints(double x1, double y1, double x2, double y2) {
  return lineThroughPointWithAngle(x1, y1, std::atan2(y2 - y1, x2 - x1));
}

void pointOnLine(const ImageLine& line, double* x, double* y) {
  if (usesYIntercept(line.theta)) {
    *x = 0;
    *y = line.intercept;
  } else {
    *x = line.intercept;
    *y = 0;
  }
}

void homogeneousFromLine(const ImageLine& line, double* a, double* b, double* c) {
  double px = 0, py = 0;
  pointOnLine(line, &px, &py);
  *a = -std::sin(line.theta);
  *b = std::cos(line.theta);
  *c = -(*a * px + *b * py);
}

ImageLine lineFromHomogeneous(double a, double b, double c) {
  // Direction (b, -a); the foot of the perpendicular from the origin lies on the line.
  const double n2 = a * a + b * b;
  return lineThroughPointWithAngle(-a * c / n2, -b * c / n2, std::atan2(-a, b));
}

double signedDistance(const ImageLine& line, double x, double y) {
  double a = 0, b = 0, c = 0;
  homogeneousFromLine(line, &a, &b, &c);
  return a * x + b * y + c;
}

bool clipLineToImage(const ImageLine& line, int width, int height, double* x1, double* y1,
                     double* x2, double* y2) {
  double px = 0, py = 0;
  pointOnLine(line, &px, &py);
  const double dx = std::cos(line.theta), dy = std::sin(line.theta);
  // Liang-Barsky on the parametric line p + t d.
  double t0 = -1e18, t1 = 1e18;
  const double lo_x = -0.5, hi_x = width - 0.5, lo_y = -0.5, hi_y = height - 0.5;
  auto clip = [&](double p, double q) {  // p * t <= q
    if (std::fabs(p) < 1e-15) return q >= 0;
    const double t = q / p;
    if (p < 0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
    return t0 <= t1;
  };
  if (!clip(-dx, px - lo_x) || !clip(dx, hi_x - px) || !clip(-dy, py - lo_y) ||
      !clip(dy, hi_y - py)) {
    return false;
  }
  *x1 = px + t0 * dx;
  *y1 = py + t0 * dy;
  *x2 = px + t1 * dx;
  *y2 = py + t1 * dy;
  return t1 - t0 > 1e-9;
}

}  // namespace rle_vision
