#include "rle_vision/ground/field_edge.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rle_vision/ground/ground_projection.h"

namespace rle_vision {
namespace {

// The polyline's samples: every step_px columns from its first point to its last, and the last.
std::vector<Eigen::Vector2d> samples(const std::vector<Eigen::Vector2d>& polyline, double step_px) {
  std::vector<Eigen::Vector2d> out;
  constexpr double kMaxWidthPx = 1e5;  // wider than any image: a broken polyline, not sampled
  for (size_t i = 0; i + 1 < polyline.size(); ++i) {
    const Eigen::Vector2d& a = polyline[i];
    const Eigen::Vector2d& b = polyline[i + 1];
    if (!a.allFinite() || !b.allFinite() || std::abs(b.x() - a.x()) > kMaxWidthPx) continue;
    const double width = b.x() - a.x();
    const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(width) / step_px)));
    for (int k = 0; k < steps; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / steps));
  }
  if (!polyline.empty() && polyline.back().allFinite()) out.push_back(polyline.back());
  return out;
}

}  // namespace

FieldEdgeOnGround projectFieldEdge(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& base_from_optical,
                                   const std::vector<Eigen::Vector2d>& polyline, double max_range_m,
                                   double bearing_step_rad, double step_px) {
  FieldEdgeOnGround edge;
  if (!(bearing_step_rad > 0) || !(step_px > 0)) return edge;
  for (const Eigen::Vector2d& pixel : samples(polyline, step_px)) {
    double ui = 0, vi = 0;
    Eigen::Vector3d ground;
    if (!std::isfinite(pixel.x()) || !std::isfinite(pixel.y())) continue;
    if (!undistortPixel(intrinsics, pixel.x(), pixel.y() - 0.5, &ui, &vi)) continue;  // the top pixel's upper side
    if (intersectGround(base_from_optical, intrinsics.pinhole, ui, vi, max_range_m, &ground)) edge.points.push_back(ground);
  }
  if (edge.points.empty()) return edge;
  // Bearings unwrapped around the first point's: a camera looking backwards sees bearings on
  // both sides of +-pi, which must stay neighbours.
  const double reference = std::atan2(edge.points.front().y(), edge.points.front().x());
  auto bearing = [reference](const Eigen::Vector3d& p) {
    return reference + std::remainder(std::atan2(p.y(), p.x()) - reference, 2 * M_PI);
  };
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (const Eigen::Vector3d& p : edge.points) {
    lowest = std::min(lowest, bearing(p));
    highest = std::max(highest, bearing(p));
  }
  const long first_bin = std::lround(lowest / bearing_step_rad), last_bin = std::lround(highest / bearing_step_rad);
  edge.bearing_step_rad = bearing_step_rad;
  edge.bearing_min_rad = first_bin * bearing_step_rad;
  edge.ranges_m.assign(static_cast<size_t>(last_bin - first_bin + 1), std::numeric_limits<float>::infinity());
  for (const Eigen::Vector3d& p : edge.points) {
    const long bin = std::lround(bearing(p) / bearing_step_rad) - first_bin;
    float& range = edge.ranges_m[static_cast<size_t>(bin)];
    range = std::min(range, static_cast<float>(p.head<2>().norm()));
  }
  return edge;
}

}  // namespace rle_vision
