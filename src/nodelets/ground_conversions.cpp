#include "ground_conversions.h"

#include <algorithm>

#include <tf2/LinearMath/Quaternion.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>

namespace rle_vision {

AttitudeFilterOptions attitudeFilterFromConfig(const GroundProjectorConfig& config) {
  AttitudeFilterOptions o;
#define RLE_ATTITUDE_FILTER_PARAM(key, member, type, default_value, min, max, description) \
  o.member = static_cast<type>(config.key);
#include "rle_vision/params/ground_params.def"
  return o;
}

GroundOptions groundFromConfig(const GroundProjectorConfig& config) {
  GroundOptions o;
#define RLE_GROUND_PARAM(key, member, type, default_value, min, max, description) o.member = static_cast<type>(config.key);
#define RLE_GROUND_ATTITUDE_PARAM RLE_GROUND_PARAM
#include "rle_vision/params/ground_params.def"
  return o;
}

BlobOutline outlineFromBlob(const Blob& blob) {
  BlobOutline outline;
  outline.left = static_cast<int>(blob.left);
  outline.top = static_cast<int>(blob.top);
  outline.right = static_cast<int>(blob.right);
  outline.bottom = static_cast<int>(blob.bottom);
  outline.contact_x = blob.cx;
  outline.contact_y = static_cast<int>(blob.bottom_at_cx);
  return outline;
}

Obstacle obstacleToMsg(const Blob& blob, const GroundObstacle& obstacle, bool occluded) {
  Obstacle o;
  o.blob_id = blob.id;
  o.color = blob.color;
  o.position.x = obstacle.position.x();
  o.position.y = obstacle.position.y();
  o.position.z = 0;
  o.width_m = static_cast<float>(obstacle.width_m);
  o.height_m = static_cast<float>(obstacle.height_m);
  o.range_m = static_cast<float>(obstacle.range_m);
  o.bearing_rad = static_cast<float>(obstacle.bearing_rad);
  o.clipped = obstacle.clipped;
  o.occluded = occluded;
  return o;
}

geometry_msgs::Quaternion rollPitchYawToMsg(double roll, double pitch, double yaw) {
  tf2::Quaternion q;
  q.setRPY(roll, pitch, yaw);
  return tf2::toMsg(q);
}

sensor_msgs::Imu attitudeImuMsg(const geometry_msgs::QuaternionStamped& attitude, const std::string& camera_frame,
                                double stddev_rad, double confidence) {
  sensor_msgs::Imu imu;
  imu.header.stamp = attitude.header.stamp;
  imu.header.frame_id = camera_frame;
  imu.orientation = attitude.quaternion;
  const double variance = stddev_rad * stddev_rad / std::max(confidence, 0.01);
  imu.orientation_covariance = {variance, 0, 0, 0, variance, 0, 0, 0, 1e6};
  imu.angular_velocity_covariance[0] = -1;
  imu.linear_acceleration_covariance[0] = -1;
  return imu;
}

}  // namespace rle_vision
