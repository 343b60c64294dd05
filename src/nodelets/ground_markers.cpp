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

}  // namespace rle_vision
