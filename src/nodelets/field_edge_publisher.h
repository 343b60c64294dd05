// The GroundProjector's field edge: the Landmark node's field boundary (image points) placed on
// the ground of the base frame, published as the nearest field edge per bearing
// (sensor_msgs/LaserScan on field_edge, in the base frame: what a costmap or a localiser reads)
// and as an rviz line strip (~field_edge_marker). Subscribes to field_boundary only while one
// of them has a subscriber. The camera's pose and intrinsics come from the GroundProjector.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <Eigen/Geometry>
#include <message_filters/subscriber.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/message_filter.h>

#include "rle_vision/FieldBoundary.h"
#include "rle_vision/ground/camera_intrinsics.h"
#include "rle_vision/ground/ground_projection.h"

namespace rle_vision {

class FieldEdgePublisher {
 public:
  struct Sources {
    // The camera's pose at the header's stamp (base from optical); false: not known.
    std::function<bool(const std_msgs::Header&, Eigen::Isometry3d*)> pose;
    // The camera's intrinsics (camera_info); false: none usable yet (the caller logs why).
    std::function<bool(CameraIntrinsics*)> intrinsics;
    std::function<GroundOptions()> options;
  };

  ~FieldEdgePublisher();
  // `tf`: with tf poses, boundaries wait in a tf2 message filter for their pose (nullptr: the
  // pose is looked up at once, as from the horizon).
  void start(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& base_frame, tf2_ros::Buffer* tf,
             int queue_size, Sources sources);

 private:
  void connectCb();
  void place(const FieldBoundaryConstPtr& msg);

  std::string base_frame_;
  Sources sources_;
  ros::Publisher pub_scan_, pub_marker_;
  message_filters::Subscriber<FieldBoundary> sub_;
  std::shared_ptr<tf2_ros::MessageFilter<FieldBoundary>> tf_filter_;
  std::mutex connect_mutex_;
  bool subscribed_ = false;
  ros::NodeHandle nh_;
};

}  // namespace rle_vision
