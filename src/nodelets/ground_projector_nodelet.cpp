// rle_vision/GroundProjector: places blobs on the flat ground in the base frame. Blobs wait in a
// tf2 message filter until the camera's pose at their stamp is known (never blocking a thread);
// the pose comes from the robot's tf (attitude_source: tf) or, on a robot without joint
// encoders, from the horizon (attitude_source: horizon), which this nodelet then broadcasts to
// tf itself. The horizon-derived attitude is also published for fusion (robot_localization).
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <message_filters/subscriber.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/message_filter.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.h"
#include "processing_stats.h"
#include "startup_params.h"
#include "rle_vision/BlobArray.h"
#include "rle_vision/GroundProjectorConfig.h"
#include "rle_vision/Horizon.h"
#include "rle_vision/ObstacleArray.h"
#include "rle_vision/config_files.h"
#include "rle_vision/ground_projection.h"

namespace rle_vision {

class GroundProjectorNodelet : public nodelet::Nodelet {
 public:
  ~GroundProjectorNodelet() override;

 private:
  void onInit() override;
  void connectCb();
  void reconfigureCb(GroundProjectorConfig& config, uint32_t level);
  void cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg);
  void horizonCb(const HorizonConstPtr& msg);
  void blobsCb(const BlobArrayConstPtr& msg);
  void blobsDroppedCb(const BlobArrayConstPtr& msg, tf2_ros::filter_failure_reasons::FilterFailureReason reason);
  void publishAttitude(const std_msgs::Header& header, double roll, double pitch, double confidence);
  void publishMarkers(const ObstacleArray& obstacles);

  // Static parameters.
  bool use_horizon_ = false;  // attitude_source: horizon
  std::string base_frame_, camera_frame_;
  bool publish_optical_tf_ = true;
  std::map<std::string, Channels> display_rgb_;  // marker colours by class name

  // Dynamic parameters: copied under the mutex, used without it.
  std::mutex config_mutex_;
  double max_range_m_ = 10.0, camera_height_m_ = 0.45, attitude_stddev_rad_ = 0.5 * M_PI / 180;
  AttitudeFilterOptions filter_options_;
  std::shared_ptr<dynamic_reconfigure::Server<GroundProjectorConfig>> reconfigure_server_;
  std::unique_ptr<GroundProjectorConfig> accepted_config_;  // shown again when a new one is refused

  std::shared_ptr<tf2_ros::Buffer> tf_buffer_;
  std::shared_ptr<tf2_ros::TransformListener> tf_listener_;
  std::shared_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  std::shared_ptr<tf2_ros::StaticTransformBroadcaster> static_broadcaster_;
  message_filters::Subscriber<BlobArray> sub_blobs_;
  std::shared_ptr<tf2_ros::MessageFilter<BlobArray>> tf_filter_;
  ros::Subscriber sub_info_, sub_horizon_;
  ros::Publisher pub_obstacles_, pub_markers_, pub_attitude_, pub_attitude_imu_;
  std::mutex connect_mutex_;
  bool blobs_subscribed_ = false;

  std::mutex info_mutex_;
  sensor_msgs::CameraInfoConstPtr camera_info_;

  // Used by horizonCb only (ROS calls it serially).
  AttitudeFilter attitude_filter_;
  bool optical_tf_sent_ = false;

  std::shared_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  ProcessingStats stats_;
};

GroundProjectorNodelet::~GroundProjectorNodelet() {
  // The filter calls back into this object: disconnect it before members go away.
  if (tf_filter_) tf_filter_->clear();
  sub_blobs_.unsubscribe();
}

void GroundProjectorNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  std::string attitude_source;
  pnh.param<std::string>("attitude_source", attitude_source, "tf");
  if (attitude_source != "tf" && attitude_source != "horizon") {
    NODELET_ERROR("~attitude_source must be 'tf' or 'horizon', got '%s': using 'tf'", attitude_source.c_str());
    attitude_source = "tf";
  }
  use_horizon_ = attitude_source == "horizon";
  pnh.param<std::string>("base_frame", base_frame_, "base_link");
  pnh.param<std::string>("camera_frame", camera_frame_, "camera_link");
  pnh.param("publish_optical_tf", publish_optical_tf_, true);
  int tf_queue_size = 30;
  pnh.param("tf_queue_size", tf_queue_size, 30);
  tf_queue_size = std::max(1, tf_queue_size);
  std::string colors_file;
  pnh.param<std::string>("colors_file", colors_file, ros::package::getPath("rle_vision") + "/config/colors.yaml");
  try {
    for (const ColorClass& c : loadColorClasses(colors_file)) display_rgb_[c.name] = c.display_rgb;
  } catch (const std::exception& e) {  // only the markers' colours depend on it
    NODELET_WARN("cannot read display colours (markers will be grey): %s", e.what());
  }

  for (const std::string& problem : startupParamProblems<GroundProjectorConfig>(pnh)) NODELET_WARN("%s", problem.c_str());
  reconfigure_server_ = std::make_shared<dynamic_reconfigure::Server<GroundProjectorConfig>>(pnh);
  reconfigure_server_->setCallback(
      [this](GroundProjectorConfig& config, uint32_t level) { reconfigureCb(config, level); });

  tf_buffer_ = std::make_shared<tf2_ros::Buffer>();
  tf_listener_ = std::make_shared<tf2_ros::TransformListener>(*tf_buffer_, nh);
  tf_broadcaster_ = std::make_shared<tf2_ros::TransformBroadcaster>();
  static_broadcaster_ = std::make_shared<tf2_ros::StaticTransformBroadcaster>();
  tf_filter_ = std::make_shared<tf2_ros::MessageFilter<BlobArray>>(*tf_buffer_, base_frame_,
                                                                    static_cast<uint32_t>(tf_queue_size), nh);
  tf_filter_->connectInput(sub_blobs_);
  tf_filter_->registerCallback([this](const BlobArrayConstPtr& msg) { blobsCb(msg); });
  tf_filter_->registerFailureCallback(
      [this](const BlobArrayConstPtr& msg, tf2_ros::filter_failure_reasons::FilterFailureReason reason) {
        blobsDroppedCb(msg, reason);
      });

  diagnostics_ = std::make_shared<diagnostic_updater::Updater>(nh, pnh, getName());
  diagnostics_->setHardwareID("none");
  diagnostics_->add("ground projector", [this](diagnostic_updater::DiagnosticStatusWrapper& s) { stats_.report(s, 5.0); });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });

  std::lock_guard<std::mutex> lock(connect_mutex_);
  const ros::SubscriberStatusCallback connect_cb = [this](const ros::SingleSubscriberPublisher&) { connectCb(); };
  pub_obstacles_ = nh.advertise<ObstacleArray>("obstacles", 10, connect_cb, connect_cb);
  pub_markers_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 2, connect_cb, connect_cb);
  pub_attitude_ = nh.advertise<geometry_msgs::QuaternionStamped>("camera_attitude", 10, connect_cb, connect_cb);
  pub_attitude_imu_ = nh.advertise<sensor_msgs::Imu>("camera_attitude_imu", 10, connect_cb, connect_cb);
  sub_info_ = nh.subscribe("camera_info", 1, &GroundProjectorNodelet::cameraInfoCb, this);
  // With the horizon as the attitude source, tf listeners anywhere depend on us: always listen.
  if (use_horizon_) sub_horizon_ = nh.subscribe("horizon", 10, &GroundProjectorNodelet::horizonCb, this);
  NODELET_INFO("placing blobs on the ground of '%s'; camera attitude from %s", base_frame_.c_str(),
               use_horizon_ ? "the horizon (broadcast to tf)" : "tf");
}

void GroundProjectorNodelet::connectCb() {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  const bool want_blobs = pub_obstacles_.getNumSubscribers() > 0 || pub_markers_.getNumSubscribers() > 0;
  if (!want_blobs && blobs_subscribed_) {
    sub_blobs_.unsubscribe();
    blobs_subscribed_ = false;
  } else if (want_blobs && !blobs_subscribed_) {
    sub_blobs_.subscribe(getNodeHandle(), "blobs", 10);
    blobs_subscribed_ = true;
  }
  if (use_horizon_) return;
  const bool want_attitude = pub_attitude_.getNumSubscribers() > 0 || pub_attitude_imu_.getNumSubscribers() > 0;
  if (!want_attitude) {
    sub_horizon_.shutdown();
  } else if (!sub_horizon_) {
    sub_horizon_ = getNodeHandle().subscribe("horizon", 10, &GroundProjectorNodelet::horizonCb, this);
  }
}

void GroundProjectorNodelet::reconfigureCb(GroundProjectorConfig& config, uint32_t /*level*/) {
  AttitudeFilterOptions options = attitudeFilterFromConfig(config);
  std::string problem = validateAttitudeFilterOptions(options);
  for (double value : {config.max_range_m, config.camera_height_m, config.attitude_stddev_deg}) {
    if (problem.empty() && !(std::isfinite(value) && value > 0)) problem = "max_range_m, camera_height_m and attitude_stddev_deg must be positive numbers";
  }
  std::lock_guard<std::mutex> lock(config_mutex_);
  if (!problem.empty()) {
    NODELET_WARN("refusing ground projector parameters: %s; keeping the previous ones", problem.c_str());
    if (accepted_config_) config = *accepted_config_;  // rqt_reconfigure shows what is in effect
    return;
  }
  accepted_config_ = std::make_unique<GroundProjectorConfig>(config);
  max_range_m_ = config.max_range_m;
  camera_height_m_ = config.camera_height_m;
  attitude_stddev_rad_ = config.attitude_stddev_deg * M_PI / 180;
  filter_options_ = options;
}

void GroundProjectorNodelet::cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg) {
  std::lock_guard<std::mutex> lock(info_mutex_);
  camera_info_ = msg;
}

void GroundProjectorNodelet::horizonCb(const HorizonConstPtr& msg) {
  double height_m;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    attitude_filter_.setOptions(filter_options_);
    height_m = camera_height_m_;
  }
  const double stamp_s = msg->header.stamp.toSec();
  if (stamp_s < attitude_filter_.lastStamp() - 1.0) {
    NODELET_WARN("horizon time went backwards (a looped bag?): the attitude filter starts over");
    attitude_filter_ = AttitudeFilter();
  }
  const AttitudeFilter::Outcome outcome =
      attitude_filter_.update(msg->found, msg->roll, msg->pitch, msg->confidence, stamp_s);
  if (msg->found && !std::isfinite(msg->pitch)) {
    NODELET_WARN_THROTTLE(10.0, "the horizon carries no pitch: the landmark node has no camera_info for %s",
                          msg->header.frame_id.c_str());
  }
  if (outcome == AttitudeFilter::Outcome::kJump) {
    NODELET_WARN_THROTTLE(5.0, "ignoring a horizon that jumps more than attitude_max_jump_deg from the predicted attitude");
  }
  if (!attitude_filter_.valid(stamp_s)) {
    if (use_horizon_) {
      NODELET_WARN_THROTTLE(5.0, "no camera attitude: no usable horizon (found, confidence >= horizon_min_confidence) "
                            "for attitude_max_hold_s; obstacles wait until the horizon is seen again");
    }
    return;
  }
  // Between accepted horizons the attitude moves on at the filter's rate.
  const double dt = stamp_s - attitude_filter_.lastStamp();
  const double roll = attitude_filter_.roll() + attitude_filter_.rollRate() * dt;
  const double pitch = attitude_filter_.pitch() + attitude_filter_.pitchRate() * dt;
  const double confidence = outcome == AttitudeFilter::Outcome::kAccepted ? msg->confidence : 0.0;

  if (use_horizon_) {
    if (publish_optical_tf_ && !optical_tf_sent_ && !msg->header.frame_id.empty()) {
      geometry_msgs::TransformStamped optical;
      optical.header.stamp = msg->header.stamp;
      optical.header.frame_id = camera_frame_;
      optical.child_frame_id = msg->header.frame_id;
      tf2::Quaternion q;
      q.setRPY(-M_PI / 2, 0, -M_PI / 2);  // REP 103: optical x right, y down, z forward
      optical.transform.rotation.x = q.x();
      optical.transform.rotation.y = q.y();
      optical.transform.rotation.z = q.z();
      optical.transform.rotation.w = q.w();
      static_broadcaster_->sendTransform(optical);
      optical_tf_sent_ = true;
    }
    geometry_msgs::TransformStamped pose;
    pose.header.stamp = msg->header.stamp;
    pose.header.frame_id = base_frame_;
    pose.child_frame_id = camera_frame_;
    pose.transform.translation.z = height_m;
    tf2::Quaternion q;
    q.setRPY(roll, pitch, 0.0);  // yaw is not observable from the horizon
    pose.transform.rotation.x = q.x();
    pose.transform.rotation.y = q.y();
    pose.transform.rotation.z = q.z();
    pose.transform.rotation.w = q.w();
    tf_broadcaster_->sendTransform(pose);
  }
  publishAttitude(msg->header, roll, pitch, confidence);
}

void GroundProjectorNodelet::publishAttitude(const std_msgs::Header& header, double roll, double pitch,
                                             double confidence) {
  if (pub_attitude_.getNumSubscribers() == 0 && pub_attitude_imu_.getNumSubscribers() == 0) return;
  double stddev;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    stddev = attitude_stddev_rad_;
  }
  tf2::Quaternion q;
  q.setRPY(roll, pitch, 0.0);
  geometry_msgs::QuaternionStamped attitude;
  attitude.header.stamp = header.stamp;
  attitude.header.frame_id = base_frame_;
  attitude.quaternion.x = q.x();
  attitude.quaternion.y = q.y();
  attitude.quaternion.z = q.z();
  attitude.quaternion.w = q.w();
  pub_attitude_.publish(attitude);

  // REP 145: orientation of camera_frame in a level frame; yaw is unknown (huge variance),
  // angular velocity and acceleration are not provided (covariance[0] = -1).
  sensor_msgs::Imu imu;
  imu.header.stamp = header.stamp;
  imu.header.frame_id = camera_frame_;
  imu.orientation = attitude.quaternion;
  const double variance = stddev * stddev / std::max(confidence, 0.01);
  imu.orientation_covariance = {variance, 0, 0, 0, variance, 0, 0, 0, 1e6};
  imu.angular_velocity_covariance[0] = -1;
  imu.linear_acceleration_covariance[0] = -1;
  pub_attitude_imu_.publish(imu);
}

void GroundProjectorNodelet::blobsDroppedCb(const BlobArrayConstPtr& msg,
                                            tf2_ros::filter_failure_reasons::FilterFailureReason reason) {
  stats_.addDrop();
  const char* why = reason == tf2_ros::filter_failure_reasons::EmptyFrameID
                        ? "the blobs carry no frame_id (the camera's images must set header.frame_id)"
                        : "no transform arrived in time";
  NODELET_WARN_THROTTLE(5.0, "dropping blobs of %.3f: %s from '%s' to '%s'. %s", msg->header.stamp.toSec(), why,
                        msg->header.frame_id.c_str(), base_frame_.c_str(),
                        use_horizon_ ? "With attitude_source horizon the horizon must be found (is the landmark node running?)."
                                     : "Is the robot's tf running (robot_state_publisher), or use attitude_source: horizon.");
}

void GroundProjectorNodelet::blobsCb(const BlobArrayConstPtr& msg) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = threadCpuMs();
  sensor_msgs::CameraInfoConstPtr info;
  {
    std::lock_guard<std::mutex> lock(info_mutex_);
    info = camera_info_;
  }
  if (!info) {
    NODELET_WARN_THROTTLE(5.0, "waiting for camera_info on %s before placing obstacles",
                          getNodeHandle().resolveName("camera_info").c_str());
    return;
  }
  CameraIntrinsics intrinsics;
  std::string problem;
  if (!intrinsicsFromInfo(*info, &intrinsics, &problem)) {
    NODELET_ERROR_THROTTLE(5.0, "cannot place obstacles: %s", problem.c_str());
    return;
  }
  if (msg->image_width != 0 && (msg->image_width != info->width || msg->image_height != info->height)) {
    NODELET_ERROR_THROTTLE(5.0, "blobs come from %ux%u images but camera_info is %ux%u: not placing them "
                           "(binning or ROI? publish the matching camera_info)",
                           msg->image_width, msg->image_height, info->width, info->height);
    return;
  }
  Eigen::Isometry3d base_from_optical;
  try {
    base_from_optical = tf2::transformToEigen(
        tf_buffer_->lookupTransform(base_frame_, msg->header.frame_id, msg->header.stamp));
  } catch (const tf2::TransformException& e) {  // the filter said it exists; it may have expired since
    NODELET_WARN_THROTTLE(5.0, "no camera pose for the blobs: %s", e.what());
    return;
  }
  double max_range_m;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    max_range_m = max_range_m_;
  }
  auto out = boost::make_shared<ObstacleArray>();
  out->header.stamp = msg->header.stamp;
  out->header.frame_id = base_frame_;
  std::vector<BlobOutline> outlines;
  for (const Blob& blob : msg->blobs) {
    BlobOutline outline;
    outline.left = static_cast<int>(blob.left);
    outline.top = static_cast<int>(blob.top);
    outline.right = static_cast<int>(blob.right);
    outline.bottom = static_cast<int>(blob.bottom);
    outline.contact_x = blob.cx;
    outline.contact_y = static_cast<int>(blob.bottom_at_cx);
    outlines.push_back(outline);
  }
  for (size_t i = 0; i < outlines.size(); ++i) {
    const Blob& blob = msg->blobs[i];
    GroundObstacle obstacle;
    if (!projectBlobToGround(intrinsics, base_from_optical, outlines[i], max_range_m, &obstacle)) {
      continue;  // above the horizon or too far: not an obstacle on the ground
    }
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
    o.occluded = contactMayBeHidden(outlines, i);
    out->obstacles.push_back(o);
  }
  pub_obstacles_.publish(out);
  if (pub_markers_.getNumSubscribers() > 0) publishMarkers(*out);
  stats_.addFrame(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                  threadCpuMs() - cpu_start_ms);
}

void GroundProjectorNodelet::publishMarkers(const ObstacleArray& obstacles) {
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
    const auto display = display_rgb_.find(o.color);
    const Channels rgb = display != display_rgb_.end() ? display->second : Channels{{160, 160, 160}};
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
  pub_markers_.publish(array);
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::GroundProjectorNodelet, nodelet::Nodelet)
