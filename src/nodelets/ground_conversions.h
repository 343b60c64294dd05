// The GroundProjector's messages and parameters to and from the core's ground projection.
#pragma once

#include <string>

#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <sensor_msgs/Imu.h>

#include "rle_vision/Blob.h"
#include "rle_vision/GroundProjectorConfig.h"
#include "rle_vision/Obstacle.h"
#include "rle_vision/ground/attitude_filter.h"
#include "rle_vision/ground/ground_projection.h"

namespace rle_vision {

// The GroundProjector's parameters as core options (from its table, ground_params.def).
AttitudeFilterOptions attitudeFilterFromConfig(const GroundProjectorConfig& config);
GroundOptions groundFromConfig(const GroundProjectorConfig& config);

// What the projection needs of a blob.
BlobOutline outlineFromBlob(const Blob& blob);

// An obstacle message for a blob placed on the ground (`occluded` is decided over all blobs).
Obstacle obstacleToMsg(const Blob& blob, const GroundObstacle& obstacle, bool occluded);

// The orientation of roll, pitch and yaw (rad, REP 103: R = Rz(yaw) Ry(pitch) Rx(roll)).
geometry_msgs::Quaternion rollPitchYawToMsg(double roll, double pitch, double yaw);

// The camera attitude for robot_localization (REP 145): the orientation of `camera_frame` in a
// level frame, its variance `stddev_rad`^2 / confidence; yaw unknown (huge variance), angular
// velocity and acceleration not provided (covariance[0] = -1).
sensor_msgs::Imu attitudeImuMsg(const geometry_msgs::QuaternionStamped& attitude, const std::string& camera_frame,
                                double stddev_rad, double confidence);

}  // namespace rle_vision
