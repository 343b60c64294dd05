// The landmark path's lines and horizon as rviz markers, one metre in front of the camera
// (rviz's camera view overlays them on the image).
#pragma once

#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include "rle_vision/ground/camera_model.h"
#include "rle_vision/landmark/landmark_detector.h"

namespace rle_vision {

visualization_msgs::MarkerArray landmarkMarkers(const std_msgs::Header& header, const LandmarkResult& result,
                                                const PinholeCamera& camera);

}  // namespace rle_vision
