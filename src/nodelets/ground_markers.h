// Obstacles as rviz markers: a cylinder per obstacle in its class's display colour, sized by
// its estimated width and height, and a label "id colour range".
#pragma once

#include <map>
#include <string>

#include <visualization_msgs/MarkerArray.h>

#include "rle_vision/ObstacleArray.h"
#include "rle_vision/color/color_class.h"

namespace rle_vision {

visualization_msgs::MarkerArray obstacleMarkers(const ObstacleArray& obstacles,
                                                const std::map<std::string, Channels>& display_rgb);

}  // namespace rle_vision
