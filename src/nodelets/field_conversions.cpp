#include "field_conversions.h"

#include <cmath>

namespace rle_vision {

FieldBoundary fieldBoundaryToMsg(const std_msgs::Header& header, const FieldBoundaryEstimate& boundary) {
  FieldBoundary msg;
  msg.header = header;
  msg.found = boundary.found;
  msg.confidence = static_cast<float>(boundary.confidence);
  for (const cv::Point2f& p : boundary.polyline) {
    geometry_msgs::Point32 point;
    point.x = p.x;
    point.y = p.y;
    msg.points.push_back(point);
  }
  return msg;
}

FieldBoundaryEstimate fieldBoundaryFromMsg(const FieldBoundary& msg) {
  FieldBoundaryEstimate boundary;
  boundary.confidence = msg.confidence;
  for (const geometry_msgs::Point32& p : msg.points) {
    // A broken message (NaN, points out of order) is no boundary: nothing is dropped by it.
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return FieldBoundaryEstimate();
    if (!boundary.polyline.empty() && p.x < boundary.polyline.back().x) return FieldBoundaryEstimate();
    boundary.polyline.emplace_back(p.x, p.y);
  }
  boundary.found = msg.found && !boundary.polyline.empty();
  return boundary;
}

}  // namespace rle_vision
