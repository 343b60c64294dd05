// Obstacles as rviz markers: a cylinder per obstacle in its class's display colour, sized by
// its estimated width and height, and a label "id colour range". The field edge as a line strip
// and as a scan.
#pragma once

#include <map>
#include <string>

#include <sensor_msgs/LaserScan.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include "rle_vision/ObstacleArray.h"
#include "rle_vision/color/color_class.h"
#include "rle_vision/ground/field_edge.h"

namespace rle_vision {

visualization_msgs::MarkerArray obstacleMarkers(const ObstacleArray& obstacles,
                                                const std::map<std::string, Channels>& display_rgb);

// The field edge on the ground as an orange line strip (header: the base frame); an empty edge
// deletes the previous strip.
visualization_msgs::Marker fieldEdgeMarker(const std_msgs::Header& header, const FieldEdgeOnGround& edge);

// The nearest field edge per bearing (REP 117: +inf where no edge point falls in a bin; range_max
// is max_range_m). An empty edge gives a scan without ranges.
sensor_msgs::LaserScan fieldEdgeScan(const std_msgs::Header& header, const FieldEdgeOnGround& edge, double max_range_m);

}  // namespace rle_vision
