// Matching detected lines with ground-truth segments, for tests and benchmarks.
#pragma once

#include <cmath>
#include <vector>

#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {

struct Segment {
  double x1, y1, x2, y2;
  double length() const { return std::hypot(x2 - x1, y2 - y1); }
  ImageLine line() const { return lineThroughPoints(x1, y1, x2, y2); }
};

// The same line: angles within `angle_tol` (rad) and intercepts within `intercept_tol` px
// (compared in one convention: where the two thetas fall on either side of the +-45 degree
// switch, the detected line's intercept is recomputed with the truth's convention). The
// detected segment must also overlap the truth segment along the line.
inline bool sameLine(const ImageLine& detected, double dx1, double dy1, double dx2, double dy2,
                     const Segment& truth, double angle_tol, double intercept_tol) {
  const ImageLine t = truth.line();
  if (lineAngleDifference(detected.theta, t.theta) > angle_tol) return false;
  // Re-express the detected line with the truth's theta convention.
  double px, py;
  pointOnLine(detected, &px, &py);
  double c = 0;
  if (usesYIntercept(t.theta)) {
    if (std::fabs(std::cos(detected.theta)) < 1e-9) return false;
    c = py - px * std::tan(detected.theta);
  } else {
    if (std::fabs(std::sin(detected.theta)) < 1e-9) return false;
    c = px - py * std::cos(detected.theta) / std::sin(detected.theta);
  }
  if (std::fabs(c - t.intercept) > intercept_tol) return false;
  // Overlap along the truth's direction.
  const double ux = (truth.x2 - truth.x1) / truth.length(), uy = (truth.y2 - truth.y1) / truth.length();
  double a0 = (dx1 - truth.x1) * ux + (dy1 - truth.y1) * uy, a1 = (dx2 - truth.x1) * ux + (dy2 - truth.y1) * uy;
  if (a0 > a1) std::swap(a0, a1);
  return a1 > 0 && a0 < truth.length();
}

struct MatchScore {
  int truths = 0, found = 0;         // truth segments, and those matched
  int detections = 0, correct = 0;   // detected lines, and those matching some truth
  double recall() const { return truths ? static_cast<double>(found) / truths : 1.0; }
  double precision() const { return detections ? static_cast<double>(correct) / detections : 1.0; }
  MatchScore& operator+=(const MatchScore& o) {
    truths += o.truths;
    found += o.found;
    detections += o.detections;
    correct += o.correct;
    return *this;
  }
};

template <typename Detected>
MatchScore scoreLines(const std::vector<Detected>& detected, const std::vector<Segment>& truth,
                      double angle_tol, double intercept_tol) {
  MatchScore s;
  s.truths = static_cast<int>(truth.size());
  s.detections = static_cast<int>(detected.size());
  for (const Segment& t : truth) {
    for (const Detected& d : detected) {
      if (sameLine(d.line, d.x1, d.y1, d.x2, d.y2, t, angle_tol, intercept_tol)) {
        ++s.found;
        break;
      }
    }
  }
  for (const Detected& d : detected) {
    for (const Segment& t : truth) {
      if (sameLine(d.line, d.x1, d.y1, d.x2, d.y2, t, angle_tol, intercept_tol)) {
        ++s.correct;
        break;
      }
    }
  }
  return s;
}

// The same edge, judged where the truth segment is (what recall and precision in benchmarks
// use): angles within `angle_tol_deg`, the detected line within `distance_tol_px` of the
// truth segment's midpoint, and the two segments overlapping along it.
template <typename Detected>
bool nearSegment(const Detected& d, const Segment& t, double angle_tol_deg, double distance_tol_px) {
  if (lineAngleDifference(d.line.theta, t.line().theta) > angle_tol_deg * M_PI / 180) return false;
  if (std::fabs(signedDistance(d.line, 0.5 * (t.x1 + t.x2), 0.5 * (t.y1 + t.y2))) > distance_tol_px) return false;
  const double ux = (t.x2 - t.x1) / t.length(), uy = (t.y2 - t.y1) / t.length();
  double a0 = (d.x1 - t.x1) * ux + (d.y1 - t.y1) * uy, a1 = (d.x2 - t.x1) * ux + (d.y2 - t.y1) * uy;
  if (a0 > a1) std::swap(a0, a1);
  return a1 > 0 && a0 < t.length();
}

// Recall over `truth`; precision: detections near any segment of `any_truth` (which may
// include edges too short to be required).
template <typename Detected>
MatchScore scoreSegments(const std::vector<Detected>& detected, const std::vector<Segment>& truth,
                         const std::vector<Segment>& any_truth, double angle_tol_deg, double distance_tol_px) {
  MatchScore s;
  s.truths = static_cast<int>(truth.size());
  s.detections = static_cast<int>(detected.size());
  for (const Segment& t : truth) {
    for (const Detected& d : detected) {
      if (nearSegment(d, t, angle_tol_deg, distance_tol_px)) {
        ++s.found;
        break;
      }
    }
  }
  for (const Detected& d : detected) {
    for (const Segment& t : any_truth) {
      if (nearSegment(d, t, angle_tol_deg, distance_tol_px)) {
        ++s.correct;
        break;
      }
    }
  }
  return s;
}

}  // namespace rle_vision
