#include "rle_vision/horizon_finder.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;

bool collinear(const DetectedLine& a, const DetectedLine& b, const HorizonOptions& o) {
  if (lineAngleDifference(a.line.theta, b.line.theta) > o.merge_angle_deg * kDeg) return false;
  // Every end point of each piece lies near the other piece's line.
  return std::fabs(signedDistance(a.line, b.x1, b.y1)) <= o.merge_distance_px &&
         std::fabs(signedDistance(a.line, b.x2, b.y2)) <= o.merge_distance_px &&
         std::fabs(signedDistance(b.line, a.x1, a.y1)) <= o.merge_distance_px &&
         std::fabs(signedDistance(b.line, a.x2, a.y2)) <= o.merge_distance_px;
}

int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

HorizonEstimate findHorizon(const std::vector<DetectedLine>& lines, int width, int height,
                            const HorizonOptions& o) {
  std::vector<int> candidates;
  for (int i = 0; i < static_cast<int>(lines.size()); ++i) {
    const DetectedLine& l = lines[i];
    if (l.length >= o.min_piece_length_px && std::fabs(l.line.theta) <= o.max_angle_deg * kDeg) {
      candidates.push_back(i);
    }
  }
  std::vector<int> parent(candidates.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t i = 0; i < candidates.size(); ++i) {
    for (size_t j = i + 1; j < candidates.size(); ++j) {
      if (collinear(lines[candidates[i]], lines[candidates[j]], o)) parent[root(parent, i)] = root(parent, j);
    }
  }

  HorizonEstimate best;
  for (size_t g = 0; g < candidates.size(); ++g) {
    if (root(parent, g) != static_cast<int>(g)) continue;
    HorizonEstimate h;
    PointSums sums;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (root(parent, i) != static_cast<int>(g)) continue;
      const DetectedLine& piece = lines[candidates[i]];
      sums.add(piece.sums);
      h.length += piece.length;
      h.votes += piece.votes;
      h.support += piece.support;
      ++h.pieces;
    }
    if (!sums.fitLine(&h.line, &h.rms)) continue;
    double cx1, cy1, cx2, cy2;
    if (!clipLineToImage(h.line, width, height, &cx1, &cy1, &cx2, &cy2)) continue;
    h.coverage = std::min(1.0, h.length / std::hypot(cx2 - cx1, cy2 - cy1));
    if (h.coverage < o.min_coverage || h.length <= best.length) continue;
    // Extent: the outermost piece end points, projected on the merged line.
    const double dx = std::cos(h.line.theta), dy = std::sin(h.line.theta);
    double px, py;
    pointOnLine(h.line, &px, &py);
    double t_min = INFINITY, t_max = -INFINITY;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (root(parent, i) != static_cast<int>(g)) continue;
      const DetectedLine& piece = lines[candidates[i]];
      for (const double t : {(piece.x1 - px) * dx + (piece.y1 - py) * dy, (piece.x2 - px) * dx + (piece.y2 - py) * dy}) {
        t_min = std::min(t_min, t);
        t_max = std::max(t_max, t);
      }
    }
    h.x1 = px + t_min * dx;
    h.y1 = py + t_min * dy;
    h.x2 = px + t_max * dx;
    h.y2 = py + t_max * dy;
    h.confidence = h.coverage * std::min(1.0, 1.5 / std::max(h.rms, 1e-9));
    h.found = true;
    best = h;
  }
  return best;
}

}  // namespace rle_vision
