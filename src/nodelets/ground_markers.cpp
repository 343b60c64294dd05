#include "ground_markers.h"

#include <algorithm>
#include <cstdio>

namespace rle_vision {

visualization_msgs::MarkerArray obstacleMarkers(const ObstacleArray& obstacles,
                                                const std::map<std::string, Channels>& display_rgb) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;
  clear.header = obstacles.header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);
  int id = 0;
  for (const Obstacle& o : obstacles.obstacles) {
    visualization_msgs::Marker cylinder;
    cylinder.header = obstacles.header;
    cylinder.ns = "obstacles";
    cylinder.id = id++;
    cylinder.type = visualization_msgs::Marker::CYLINDER;
    cylinder.action = visualization_msgs::Marker::ADD;
    const double height = o.height_m > 0 ? o.height_m : 0.1;
    cylinder.pose.position = o.position;
    cylinder.pose.position.z = 0.5 * height;
    cylinder.pose.orientation.w = 1;
    cylinder.scale.x = cylinder.scale.y = std::max(0.02f, o.width_m);
    cylinder.scale.z = height;
    const auto display = display_rgb.find(o.color);
    const Channels rgb = display != display_rgb.end() ? display->second : Channels{{160, 160, 160}};
    cylinder.color.r = static_cast<float>(rgb[0] / 255.0);
    cylinder.color.g = static_cast<float>(rgb[1] / 255.0);
    cylinder.color.b = static_cast<float>(rgb[2] / 255.0);
    cylinder.color.a = o.occluded || o.clipped ? 0.35f : 0.8f;  // faint: the position is only a bound
    array.markers.push_back(cylinder);

    visualization_msgs::Marker text = cylinder;
    text.ns = "labels";
    text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    text.pose.position.z = height + 0.08;
    text.scale.x = text.scale.y = 0;
    text.scale.z = 0.08;
    text.color.r = text.color.g = text.color.b = text.color.a = 1.0f;
    char label[64];
    // Hidden or cut-off contact points lie nearer than the projection: the range is a bound.
    std::snprintf(label, sizeof(label), "%u %s %s%.2f m", o.blob_id, o.color.c_str(),
                  o.occluded || o.clipped ? "< " : "", o.range_m);
    text.text = label;
    array.markers.push_back(text);
  }
  return array;
}

visualization_msgs::Marker fieldEdgeMarker(const std_msgs::Header& header, const FieldEdgeOnGround& edge) {
  visualization_msgs::Marker strip;
  strip.header = header;
  strip.ns = "field_edge";
  strip.id = 0;
  strip.type = visualization_msgs::Marker::LINE_STRIP;
  strip.action = edge.points.empty() ? visualization_msgs::Marker::DELETE : visualization_msgs::Marker::ADD;
  strip.pose.orientation.w = 1;
  strip.scale.x = 0.03;  // line width, m
  strip.color.r = 1.0f;
  strip.color.g = 0.55f;
  strip.color.b = 0.0f;
  strip.color.a = 0.9f;
  for (const Eigen::Vector3d& p : edge.points) {
    geometry_msgs::Point point;
    point.x = p.x();
    point.y = p.y();
    point.z = 0.01;  // just above the ground, so that a grid does not hide it
    strip.points.push_back(point);
  }
  return strip;
}

sensor_msgs::LaserScan fieldEdgeScan(const std_msgs::Header& header, const FieldEdgeOnGround& edge, double max_range_m) {
  sensor_msgs::LaserScan scan;
  scan.header = header;
  scan.range_min = 0;
  scan.range_max = static_cast<float>(max_range_m);
  if (edge.ranges_m.empty()) return scan;
  scan.angle_increment = static_cast<float>(edge.bearing_step_rad);
  scan.angle_min = static_cast<float>(edge.bearing_min_rad);
  scan.angle_max = static_cast<float>(edge.bearing_min_rad + (edge.ranges_m.size() - 1) * edge.bearing_step_rad);
  scan.ranges = edge.ranges_m;
  return scan;
}

}  // namespace rle_vision
