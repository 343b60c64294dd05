#include "rle_vision/landmark/ridge_fit.h"

#include <algorithm>
#include <cmath>

#include "landmark/ridge_profile.h"

namespace rle_vision {
namespace {

// a x + b y + c = 0 with (a, b) the unit normal: distances without trigonometry per point.
struct Normal {
  double a, b, c;
  explicit Normal(const ImageLine& line) { homogeneousFromLine(line, &a, &b, &c); }
  double distance(double x, double y) const { return a * x + b * y + c; }
};

// Bilinear edge value at (x, y); 0 outside the image.
inline double sample(const cv::Mat& edges, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= edges.cols || y0 + 1 >= edges.rows) return 0;
  const double fx = x - x0, fy = y - y0;
  const uint8_t* r0 = edges.ptr<uint8_t>(y0) + x0;
  const uint8_t* r1 = edges.ptr<uint8_t>(y0 + 1) + x0;
  return (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
}

// Ridge points: every pixel along the line, the edge profile perpendicular to it (half-pixel
// steps, bilinear) where it peaks above min_strength; its centre is the centroid of the
// profile above half the edge threshold. Perpendicular profiles stay symmetric at end caps,
// unlike row or column profiles of a slanted line.
}  // namespace

void RidgeFitter::ridgePoints(const cv::Mat& edges, const ImageLine& line, double t0, double t1,
                              const RidgeFitOptions& o) {
  std::vector<RidgePoint>* const out = &points_;
  out->clear();
  const double c = std::cos(line.theta), s = std::sin(line.theta);
  const double nx = -s, ny = c;
  double px, py;
  pointOnLine(line, &px, &py);
  const double t_origin = px * c + py * s;
  constexpr double kStep = 0.5;
  const int half = static_cast<int>(std::ceil(o.half_width_px / kStep));
  const int samples = 2 * half + 1;
  profile_.resize(samples);
  offset_x_.resize(samples);
  offset_y_.resize(samples);
  double* const profile = profile_.data();
  for (int k = -half; k <= half; ++k) {
    offset_x_[k + half] = k * kStep * nx;
    offset_y_[k + half] = k * kStep * ny;
  }
  const double floor = 0.5 * o.min_strength;
  // Samples whose 2x2 neighbourhood is inside the image: x in [0, cols - 1), y in [0, rows - 1).
  const double x_max = edges.cols - 1, y_max = edges.rows - 1;
  const size_t step = edges.step[0];
  for (double t = std::ceil(t0); t <= t1; t += 1.0) {
    const double bx = px + (t - t_origin) * c, by = py + (t - t_origin) * s;
    const double ax = bx + offset_x_[0], ay = by + offset_y_[0];  // the profile's ends
    const double zx = bx + offset_x_[samples - 1], zy = by + offset_y_[samples - 1];
    if (std::min(ax, zx) >= 0 && std::max(ax, zx) < x_max && std::min(ay, zy) >= 0 && std::max(ay, zy) < y_max) {
      // The whole profile is inside: no bounds checks, and truncation is floor.
      ridge::profileInsideFastest(edges.data, step, bx, by, offset_x_.data(), offset_y_.data(), samples, profile);
    } else {
      for (int i = 0; i < samples; ++i) profile[i] = sample(edges, bx + offset_x_[i], by + offset_y_[i]);
    }
    // The strongest sample's value.
    double peak = profile[0];
    for (int k = 1; k < samples; ++k) peak = std::max(peak, profile[k]);
    if (peak < o.min_strength) continue;
    // The centre: the centroid of the strong samples across the window, so a thin bar's two
    // edges (however deep the dip between them) give the bar's centre line.
    // Samples of at least half the peak: a bar's two equal edges count, a weaker edge nearby
    // does not.
    const double level = std::max(floor, 0.5 * peak);
    double weight = 0, moment = 0;
    for (int k = 0; k < samples; ++k) {
      if (profile[k] < level) continue;
      const double w = profile[k] - floor;
      if (w <= 0) continue;
      weight += w;
      moment += w * (k - half) * kStep;
    }
    const double offset = moment / weight;
    out->push_back({bx + offset * nx, by + offset * ny, t});
  }
}

namespace {

// The median of v[0..4] by a few compares (nth_element on 5 values is far slower).
inline double median5(const double* v) {
  double a = v[0], b = v[1], c = v[2], d = v[3], e = v[4];
  if (a > b) std::swap(a, b);
  if (c > d) std::swap(c, d);
  // The smaller of a and c has three values above it, so it is below the median: replace it
  // with e. The median is then the second smallest of the four left.
  if (a < c) {
    a = e;
    if (a > b) std::swap(a, b);
  } else {
    c = e;
    if (c > d) std::swap(c, d);
  }
  return a < c ? std::min(b, c) : std::min(a, d);
}

// The total-least-squares line through points[first..last] (at least 3), with its sums.
template <class Point>
bool fitPoints(const std::vector<Point>& points, size_t first, size_t last, RidgeFit* fit) {
  PointSums s;
  for (size_t i = first; i <= last; ++i) s.addPixel(points[i].x, points[i].y);
  if (s.n < 3 || !s.fitLine(&fit->line, &fit->rms)) return false;
  fit->sums = s;
  return true;
}

}  // namespace

// Douglas-Peucker on ridge points[first..last] (inliers, ordered along the line): a stretch
// that bends more than split_px away from its fitted line splits at the farthest point. The
// deviation is median-filtered over 5 points, so a corner splits a stretch and a stray point
// does not.
void RidgeFitter::splitAndFit(size_t first, size_t last, const RidgeFitOptions& o, double min_length, int depth,
                              std::vector<RidgeFit>* fits) {
  const std::vector<RidgePoint>& points = inliers_;
  if (last <= first + 2 || points[last].t - points[first].t < min_length) return;
  RidgeFit fit;
  if (!fitPoints(points, first, last, &fit)) return;
  // Deviation from the chord between the stretch's ends (the classic Douglas-Peucker measure:
  // at a corner it peaks at the vertex, where a least-squares line would peak at the ends).
  std::vector<double>& deviation = deviation_;
  deviation.resize(last - first + 1);
  const Normal chord(lineThroughPoints(points[first].x, points[first].y, points[last].x, points[last].y));
  for (size_t i = first; i <= last; ++i) deviation[i - first] = std::fabs(chord.distance(points[i].x, points[i].y));
  size_t farthest = first;
  double largest = 0;
  for (size_t i = first + 2; i + 2 <= last; ++i) {
    const double median = median5(&deviation[i - first - 2]);
    if (median > largest) {
      largest = median;
      farthest = i;
    }
  }
  if (largest > o.split_px && depth < 8) {
    // A corner also turns: split only when the two sides' own lines differ in angle (a
    // straight edge whose end points sit on bent corners does not).
    RidgeFit head, tail;
    const bool turns = farthest >= first + 3 && last >= farthest + 3 && fitPoints(points, first, farthest, &head) &&
                       fitPoints(points, farthest, last, &tail) &&
                       lineAngleDifference(head.line.theta, tail.line.theta) > o.split_angle_deg * M_PI / 180;
    if (turns) {
      splitAndFit(first, farthest, o, min_length, depth + 1, fits);
      splitAndFit(farthest, last, o, min_length, depth + 1, fits);
      return;
    }
  }
  // The final fit leaves out the ends, where a corner's other edge bends the ridge, and stray
  // points (beyond three median deviations); the end points still come from the whole stretch.
  const double trim = std::min(o.end_trim_px, 0.15 * (points[last].t - points[first].t));
  const Normal normal(fit.line);
  for (size_t i = first; i <= last; ++i) deviation[i - first] = std::fabs(normal.distance(points[i].x, points[i].y));
  std::nth_element(deviation.begin(), deviation.begin() + deviation.size() / 2, deviation.end());
  const double stray = std::max(0.5, 3.0 * 1.4826 * deviation[deviation.size() / 2]);
  PointSums inner;
  for (size_t i = first; i <= last; ++i) {
    if (points[i].t < points[first].t + trim || points[i].t > points[last].t - trim) continue;
    if (std::fabs(normal.distance(points[i].x, points[i].y)) <= stray) inner.addPixel(points[i].x, points[i].y);
  }
  double inner_rms = 0;
  ImageLine inner_line;
  if (inner.n >= 3 && inner.fitLine(&inner_line, &inner_rms)) {
    fit.line = inner_line;
    fit.rms = inner_rms;
    fit.sums = inner;
  }
  fit.points = static_cast<int>(last - first + 1);
  // End points: the first and last ridge point projected on the fitted line.
  const Normal final_normal(fit.line);
  const double d1 = final_normal.distance(points[first].x, points[first].y);
  const double d2 = final_normal.distance(points[last].x, points[last].y);
  fit.x1 = points[first].x - d1 * final_normal.a;
  fit.y1 = points[first].y - d1 * final_normal.b;
  fit.x2 = points[last].x - d2 * final_normal.a;
  fit.y2 = points[last].y - d2 * final_normal.b;
  fits->push_back(fit);
}

void RidgeFitter::fit(const cv::Mat& edges, const ImageLine& start, double t0, double t1, const RidgeFitOptions& o,
                      double min_length, std::vector<RidgeFit>* fits) {
  ridgePoints(edges, start, t0, t1, o);
  fitRobustly(start, o, min_length, fits);
}

void RidgeFitter::fitRobustly(const ImageLine& start, const RidgeFitOptions& o, double min_length,
                              std::vector<RidgeFit>* fits) {
  fits->clear();
  const std::vector<RidgePoint>& points = points_;
  std::vector<RidgePoint>& inliers = inliers_;
  std::vector<double>& residuals = residuals_;
  std::vector<double>& sorted = sorted_;
  if (points.size() < 3) return;
  // A robust line through all ridge points: fit, keep the points within a cut that shrinks to
  // three times the median residual (ignoring neighbouring ridges near corners), fit again.
  ImageLine line = start;
  residuals.resize(points.size());
  double cut = 2 * o.inlier_px;
  for (int round = 0; round < 3; ++round) {
    const Normal normal(line);
    for (size_t i = 0; i < points.size(); ++i) residuals[i] = std::fabs(normal.distance(points[i].x, points[i].y));
    sorted = residuals;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    cut = std::min(round == 0 ? 2 * o.inlier_px : o.inlier_px, std::max(0.5, 3.0 * 1.4826 * sorted[sorted.size() / 2]));
    PointSums kept;
    for (size_t i = 0; i < points.size(); ++i) {
      if (residuals[i] <= cut) kept.addPixel(points[i].x, points[i].y);
    }
    double rms = 0;
    if (kept.n < 3 || !kept.fitLine(&line, &rms)) return;
  }
  // Stretches of points within inlier_px of that line (others are skipped) whose consecutive
  // points are at most max_gap apart; each is split where it bends, and fitted. (The band is
  // wider than the cut above so that a bend shows as a growing deviation.)
  inliers.clear();
  const Normal normal(line);
  for (const RidgePoint& p : points) {
    if (std::fabs(normal.distance(p.x, p.y)) <= std::max(cut, o.inlier_px)) inliers.push_back(p);
  }
  size_t first = 0;
  for (size_t i = 1; i <= inliers.size(); ++i) {
    if (i < inliers.size() && inliers[i].t - inliers[i - 1].t <= o.max_gap_px) continue;
    if (!inliers.empty()) splitAndFit(first, i - 1, o, min_length, 0, fits);
    first = i;
  }
}

}  // namespace rle_vision
