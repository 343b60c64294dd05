#include "field_edge_publisher.h"

#include <cmath>

#include <sensor_msgs/LaserScan.h>
#include <visualization_msgs/Marker.h>

#include "field_conversions.h"
#include "ground_markers.h"
#include "rle_vision/ground/field_edge.h"

namespace rle_vision {

FieldEdgePublisher::~FieldEdgePublisher() {
  // The filter calls back into this object: disconnect it before members go away.
  if (tf_filter_) tf_filter_->clear();
  sub_.unsubscribe();
}

void FieldEdgePublisher::start(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& base_frame,
                               tf2_ros::Buffer* tf, int queue_size, Sources sources) {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  nh_ = nh;
  base_frame_ = base_frame;
  sources_ = std::move(sources);
  if (tf) {
    tf_filter_ = std::make_shared<tf2_ros::MessageFilter<FieldBoundary>>(*tf, base_frame, static_cast<uint32_t>(queue_size), nh);
    tf_filter_->connectInput(sub_);
    tf_filter_->registerCallback([this](const FieldBoundaryConstPtr& msg) { place(msg); });
  } else {
    sub_.registerCallback([this](const FieldBoundaryConstPtr& msg) { place(msg); });
  }
  const ros::SubscriberStatusCallback connect_cb = [this](const ros::SingleSubscriberPublisher&) { connectCb(); };
  pub_scan_ = nh.advertise<sensor_msgs::LaserScan>("field_edge", 5, connect_cb, connect_cb);
  pub_marker_ = pnh.advertise<visualization_msgs::Marker>("field_edge_marker", 2, connect_cb, connect_cb);
}

void FieldEdgePublisher::connectCb() {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  const bool wanted = pub_scan_.getNumSubscribers() > 0 || pub_marker_.getNumSubscribers() > 0;
  if (wanted && !subscribed_) {
    sub_.subscribe(nh_, "field_boundary", 5);
  } else if (!wanted && subscribed_) {
    sub_.unsubscribe();
  }
  subscribed_ = wanted;
}

void FieldEdgePublisher::place(const FieldBoundaryConstPtr& msg) {
  Eigen::Isometry3d base_from_optical;
  CameraIntrinsics intrinsics;
  if (!sources_.pose(msg->header, &base_from_optical)) return;
  const GroundOptions options = sources_.options();
  FieldEdgeOnGround edge;
  const FieldBoundaryEstimate boundary = fieldBoundaryFromMsg(*msg);  // a broken message is no boundary
  if (boundary.found && sources_.intrinsics(&intrinsics)) {
    std::vector<Eigen::Vector2d> polyline;
    for (const cv::Point2f& p : boundary.polyline) polyline.emplace_back(p.x, p.y);
    // Sampled every 2 px: the boundary is a polyline, and finer bearings than that are noise.
    edge = projectFieldEdge(intrinsics, base_from_optical, polyline, options.max_range_m,
                            options.field_edge_bearing_step_deg * M_PI / 180.0, 2.0);
  }
  std_msgs::Header header = msg->header;
  header.frame_id = base_frame_;
  pub_scan_.publish(fieldEdgeScan(header, edge, options.max_range_m));
  if (pub_marker_.getNumSubscribers() > 0) pub_marker_.publish(fieldEdgeMarker(header, edge));
}

}  // namespace rle_vision
