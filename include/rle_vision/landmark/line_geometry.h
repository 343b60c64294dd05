// Straight lines in the paper's parameter space (docs/ARCHITECTURE.md, Conventions), image coordinates
// (x right, y down, pixel centres at integer coordinates).
//
// theta: angle of the line to the image horizontal, in (-pi/2, pi/2]; the line's direction
//        is (cos theta, sin theta).
// intercept: y at x = 0 when -pi/4 < theta <= pi/4, otherwise x at y = 0.
// At theta = -pi/4 both intercepts are equal; at +pi/4 they are additive inverses.
#pragma once

#include <cmath>

namespace rle_vision {

struct ImageLine {
  double theta = 0;
  double intercept = 0;
};

inline bool usesYIntercept(double theta) { return theta > -M_PI / 4 && theta <= M_PI / 4; }

// Maps any angle to the equivalent line angle in (-pi/2, pi/2].
double normalizeLineAngle(double theta);

// Smallest angle between two undirected lines, in [0, pi/2].
double lineAngleDifference(double theta_a, double theta_b);

ImageLine lineThroughPoints(double x1, double y1, double x2, double y2);
ImageLine lineThroughPointWithAngle(double x, double y, double theta);

// a*x + b*y + c = 0 (a, b not both zero).
ImageLine lineFromHomogeneous(double a, double b, double c);
// Unit normal form: a*x + b*y + c = 0 with a^2 + b^2 = 1, (a, b) = (-sin theta, cos theta).
void homogeneousFromLine(const ImageLine& line, double* a, double* b, double* c);

// Signed distance of a point from the line, px (positive on the side of the normal
// (-sin theta, cos theta), i.e. below a horizontal line).
double signedDistance(const ImageLine& line, double x, double y);

// A point on the line (the intercept point).
void pointOnLine(const ImageLine& line, double* x, double* y);

// The segment of the line inside the image [-0.5, width - 0.5] x [-0.5, height - 0.5].
// Returns false when the line misses the image.
bool clipLineToImage(const ImageLine& line, int width, int height, double* x1, double* y1,
                     double* x2, double* y2);

// Intercept of the line of angle `theta` through (x, y), in the convention `theta` selects.
double interceptFor(double theta, double x, double y);

}  // namespace rle_vision
