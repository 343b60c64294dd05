#include "landmark_markers.h"

namespace rle_vision {
namespace {

geometry_msgs::Point backProject(const PinholeCamera& camera, double u, double v) {
  // The ray through (u, v) at 1 m depth in the optical frame.
  geometry_msgs::Point p;
  p.x = (u - camera.cx) / camera.fx;
  p.y = (v - camera.cy) / camera.fy;
  p.z = 1.0;
  return p;
}

}  // namespace

visualization_msgs::MarkerArray landmarkMarkers(const std_msgs::Header& header, const LandmarkResult& result,
                                                const PinholeCamera& camera) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker lines;
  lines.header = header;
  lines.ns = "lines";
  lines.id = 0;
  lines.type = visualization_msgs::Marker::LINE_LIST;
  lines.action = visualization_msgs::Marker::ADD;
  lines.pose.orientation.w = 1.0;
  lines.scale.x = 0.003;
  lines.color.g = 1.0;
  lines.color.a = 1.0;
  for (const DetectedLine& l : result.lines) {
    lines.points.push_back(backProject(camera, l.x1, l.y1));
    lines.points.push_back(backProject(camera, l.x2, l.y2));
  }
  if (lines.points.empty()) lines.action = visualization_msgs::Marker::DELETE;
  array.markers.push_back(lines);
  visualization_msgs::Marker horizon = lines;
  horizon.ns = "horizon";
  horizon.type = visualization_msgs::Marker::LINE_STRIP;
  horizon.scale.x = 0.008;
  horizon.color.r = 0.0;
  horizon.color.g = 1.0;
  horizon.color.b = 1.0;
  horizon.points.clear();
  horizon.action = visualization_msgs::Marker::DELETE;
  if (result.horizon.found) {
    horizon.action = visualization_msgs::Marker::ADD;
    horizon.points.push_back(backProject(camera, result.horizon.x1, result.horizon.y1));
    horizon.points.push_back(backProject(camera, result.horizon.x2, result.horizon.y2));
  }
  array.markers.push_back(horizon);
  return array;
}

}  // namespace rle_vision
