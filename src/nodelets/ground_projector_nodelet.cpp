// rle_vision/GroundProjector: places blobs on the flat ground in the base frame. The camera's
// pose comes from the robot's tf (attitude_source: tf), blobs waiting in a tf2 message filter
// until it is known at their stamp (never blocking a thread); or, on a robot without joint
// encoders, from the horizon (attitude_source: horizon): the core's attitude timeline gives
// the pose at each blob's stamp (blobs newer than the last horizon wait for the next), and
// this nodelet broadcasts it to tf for others. The horizon-derived attitude is also published
// for fusion (robot_localization).
#include <chrono>
#include <cmath>
#include <deque>
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
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/message_filter.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "field_edge_publisher.h"
#include "ground_conversions.h"
#include "ground_markers.h"
#include "node_settings.h"
#include "image_conversions.h"
#include "processing_stats.h"
#include "startup_params.h"
#include "rle_vision/BlobArray.h"
#include "rle_vision/GroundProjectorConfig.h"
#include "rle_vision/Horizon.h"
#include "rle_vision/ObstacleArray.h"
#include "rle_vision/ground/attitude_filter.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/ground/ground_projection.h"
#include "rle_vision/common/wait_watchdog.h"

namespace rle_vision {

class GroundProjectorNodelet : public nodelet::Nodelet {
 public:
  ~GroundProjectorNodelet() override;

 private:
  void onInit() override;
  void readStaticParams(ros::NodeHandle& pnh);
  void advertiseAndSubscribe(ros::NodeHandle& nh);
  void connectCb();
  void reconfigureCb(GroundProjectorConfig& config, uint32_t level);
  void cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg);
  void horizonCb(const HorizonConstPtr& msg);
  void blobsWithTfCb(const BlobArrayConstPtr& msg);
  void blobsWithHorizonCb(const BlobArrayConstPtr& msg);
  void placePendingBlobs();
  void warnIfStuck();
  void blobsDroppedCb(const BlobArrayConstPtr& msg, tf2_ros::filter_failure_reasons::FilterFailureReason reason);
  void broadcastPose(const std_msgs::Header& header, double roll, double pitch);
  void place(const BlobArray& msg, const Eigen::Isometry3d& base_from_optical);
  void publishAttitude(const std_msgs::Header& header, const AttitudeTimeline::Attitude& attitude);
  bool fieldEdgePose(const std_msgs::Header& header, Eigen::Isometry3d* base_from_optical);
  bool fieldEdgeIntrinsics(CameraIntrinsics* intrinsics);

  // Static parameters.
  bool use_horizon_ = false;  // attitude_source: horizon
  std::string base_frame_, camera_frame_;
  bool publish_optical_tf_ = true;
  int queue_size_ = 30;  // blob messages waiting for their camera pose
  // Said within a second when no blobs can be placed (tf mode), whatever the queue's length.
  WaitWatchdog pose_wait_{1.0};
  ros::WallTimer stuck_timer_;
  std::mutex blob_frame_mutex_;
  std::string blob_frame_;  // of the newest blobs, for the warning
  std::map<std::string, Channels> display_rgb_;  // marker colours by class name

  // Dynamic parameters: copied under the mutex, used without it.
  std::mutex config_mutex_;
  GroundOptions ground_options_;
  AttitudeFilterOptions filter_options_;
  std::shared_ptr<dynamic_reconfigure::Server<GroundProjectorConfig>> reconfigure_server_;
  std::unique_ptr<GroundProjectorConfig> accepted_config_;  // shown again when a new one is refused

  std::shared_ptr<tf2_ros::Buffer> tf_buffer_;
  std::shared_ptr<tf2_ros::TransformListener> tf_listener_;
  std::shared_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  std::shared_ptr<tf2_ros::StaticTransformBroadcaster> static_broadcaster_;
  message_filters::Subscriber<BlobArray> sub_blobs_;
  std::shared_ptr<tf2_ros::MessageFilter<BlobArray>> tf_filter_;  // tf mode
  ros::Subscriber sub_info_, sub_horizon_;
  ros::Publisher pub_obstacles_, pub_markers_, pub_attitude_, pub_attitude_imu_;
  std::mutex connect_mutex_;
  bool blobs_subscribed_ = false;

  std::mutex info_mutex_;
  sensor_msgs::CameraInfoConstPtr camera_info_;

  // The attitude from the horizon and (horizon mode) the blobs waiting for it; horizon and
  // blob callbacks may run on different threads.
  std::mutex attitude_mutex_;
  AttitudeTimeline attitude_;
  std::deque<BlobArrayConstPtr> pending_blobs_;
  bool optical_tf_sent_ = false;

  FieldEdgePublisher field_edge_;  // the field boundary on the ground

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
  readStaticParams(pnh);
  for (const std::string& problem : startupParamProblems<GroundProjectorConfig>(pnh)) NODELET_WARN("%s", problem.c_str());
  reconfigure_server_ = std::make_shared<dynamic_reconfigure::Server<GroundProjectorConfig>>(pnh);
  reconfigure_server_->setCallback(
      [this](GroundProjectorConfig& config, uint32_t level) { reconfigureCb(config, level); });

  tf_buffer_ = std::make_shared<tf2_ros::Buffer>();
  tf_listener_ = std::make_shared<tf2_ros::TransformListener>(*tf_buffer_, nh);
  tf_broadcaster_ = std::make_shared<tf2_ros::TransformBroadcaster>();
  static_broadcaster_ = std::make_shared<tf2_ros::StaticTransformBroadcaster>();
  if (use_horizon_) {
    sub_blobs_.registerCallback([this](const BlobArrayConstPtr& msg) { blobsWithHorizonCb(msg); });
  } else {
    tf_filter_ = std::make_shared<tf2_ros::MessageFilter<BlobArray>>(*tf_buffer_, base_frame_,
                                                                      static_cast<uint32_t>(queue_size_), nh);
    tf_filter_->connectInput(sub_blobs_);
    tf_filter_->registerCallback([this](const BlobArrayConstPtr& msg) { blobsWithTfCb(msg); });
    sub_blobs_.registerCallback([this](const BlobArrayConstPtr& msg) {
      pose_wait_.received(ros::WallTime::now().toSec());
      std::lock_guard<std::mutex> lock(blob_frame_mutex_);
      blob_frame_ = msg->header.frame_id;
    });
    stuck_timer_ = nh.createWallTimer(ros::WallDuration(0.25), [this](const ros::WallTimerEvent&) { warnIfStuck(); });
    tf_filter_->registerFailureCallback(
        [this](const BlobArrayConstPtr& msg, tf2_ros::filter_failure_reasons::FilterFailureReason reason) {
          blobsDroppedCb(msg, reason);
        });
  }

  diagnostics_ = std::make_shared<diagnostic_updater::Updater>(nh, pnh, getName());
  diagnostics_->setHardwareID("none");
  diagnostics_->add("ground projector", [this](diagnostic_updater::DiagnosticStatusWrapper& s) { stats_.report(s, 5.0); });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });
  advertiseAndSubscribe(nh);
  FieldEdgePublisher::Sources sources;
  sources.pose = [this](const std_msgs::Header& header, Eigen::Isometry3d* pose) { return fieldEdgePose(header, pose); };
  sources.intrinsics = [this](CameraIntrinsics* intrinsics) { return fieldEdgeIntrinsics(intrinsics); };
  sources.options = [this] {
    std::lock_guard<std::mutex> lock(config_mutex_);
    return ground_options_;
  };
  field_edge_.start(nh, pnh, base_frame_, use_horizon_ ? nullptr : tf_buffer_.get(), queue_size_, std::move(sources));
  NODELET_INFO("placing blobs on the ground of '%s'; camera attitude from %s", base_frame_.c_str(),
               use_horizon_ ? "the horizon (broadcast to tf)" : "tf");
}

// What the GroundProjector reads once at start: the RLE_GROUND_SETTING lines of its table.
struct GroundSettings {
#define RLE_GROUND_SETTING(key, type, default_value, min, max, description) type key = default_value;
#include "rle_vision/params/ground_params.def"
};

void GroundProjectorNodelet::readStaticParams(ros::NodeHandle& pnh) {
  GroundSettings settings;
  std::vector<std::string> problems;
#define RLE_GROUND_SETTING(key, type, default_value, min, max, description) \
  readSetting(pnh, #key, &settings.key, min, max, &problems);
#include "rle_vision/params/ground_params.def"
  for (const std::string& problem : problems) NODELET_WARN("%s", problem.c_str());
  if (settings.attitude_source != "tf" && settings.attitude_source != "horizon") {
    NODELET_ERROR("~attitude_source must be 'tf' or 'horizon', got '%s': using 'tf'", settings.attitude_source.c_str());
    settings.attitude_source = "tf";
  }
  use_horizon_ = settings.attitude_source == "horizon";
  base_frame_ = settings.base_frame;
  camera_frame_ = settings.camera_frame;
  publish_optical_tf_ = settings.publish_optical_tf;
  queue_size_ = settings.tf_queue_size;
  const std::string colors_file =
      settings.colors_file.empty() ? ros::package::getPath("rle_vision") + "/config/colors.yaml" : settings.colors_file;
  try {
    for (const ColorClass& c : loadColorClasses(colors_file)) display_rgb_[c.name] = c.display_rgb;
  } catch (const std::exception& e) {  // only the markers' colours depend on it
    NODELET_WARN("cannot read display colours (markers will be grey): %s", e.what());
  }
}

void GroundProjectorNodelet::advertiseAndSubscribe(ros::NodeHandle& nh) {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  const ros::SubscriberStatusCallback connect_cb = [this](const ros::SingleSubscriberPublisher&) { connectCb(); };
  pub_obstacles_ = nh.advertise<ObstacleArray>("obstacles", 10, connect_cb, connect_cb);
  pub_markers_ = getPrivateNodeHandle().advertise<visualization_msgs::MarkerArray>("markers", 2, connect_cb, connect_cb);
  pub_attitude_ = nh.advertise<geometry_msgs::QuaternionStamped>("camera_attitude", 10, connect_cb, connect_cb);
  pub_attitude_imu_ = nh.advertise<sensor_msgs::Imu>("camera_attitude_imu", 10, connect_cb, connect_cb);
  sub_info_ = nh.subscribe("camera_info", 1, &GroundProjectorNodelet::cameraInfoCb, this);
  // With the horizon as the attitude source, tf listeners anywhere depend on us: always listen.
  if (use_horizon_) sub_horizon_ = nh.subscribe("horizon", 10, &GroundProjectorNodelet::horizonCb, this);
}

void GroundProjectorNodelet::connectCb() {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  const bool want_blobs = pub_obstacles_.getNumSubscribers() > 0 || pub_markers_.getNumSubscribers() > 0;
  if (!want_blobs && blobs_subscribed_) {
    sub_blobs_.unsubscribe();
    blobs_subscribed_ = false;
    pose_wait_.handled();  // nobody wants them placed: not stuck
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
  const GroundOptions ground = groundFromConfig(config);
  std::string problem = validateAttitudeFilterOptions(options);
  for (double value : {ground.max_range_m, ground.camera_height_m, ground.attitude_stddev_deg, ground.field_edge_bearing_step_deg}) {
    if (problem.empty() && !(std::isfinite(value) && value > 0)) {
      problem = "max_range_m, camera_height_m, attitude_stddev_deg and field_edge_bearing_step_deg must be positive numbers";
    }
  }
  std::lock_guard<std::mutex> lock(config_mutex_);
  if (!problem.empty()) {
    NODELET_WARN("refusing ground projector parameters: %s; keeping the previous ones", problem.c_str());
    if (accepted_config_) config = *accepted_config_;  // rqt_reconfigure shows what is in effect
    return;
  }
  accepted_config_ = std::make_unique<GroundProjectorConfig>(config);
  ground_options_ = ground;
  filter_options_ = options;
}

void GroundProjectorNodelet::cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg) {
  std::lock_guard<std::mutex> lock(info_mutex_);
  camera_info_ = msg;
}

void GroundProjectorNodelet::horizonCb(const HorizonConstPtr& msg) {
  AttitudeFilterOptions options;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    options = filter_options_;
  }
  if (msg->found && !std::isfinite(msg->pitch)) {
    NODELET_WARN_THROTTLE(10.0, "the horizon carries no pitch: the landmark node has no camera_info for %s",
                          msg->header.frame_id.c_str());
  }
  AttitudeTimeline::Update update;
  {
    std::lock_guard<std::mutex> lock(attitude_mutex_);
    attitude_.setOptions(options);
    update = attitude_.addHorizon(msg->found, msg->roll, msg->pitch, msg->confidence, msg->header.stamp.toSec());
  }
  if (update.restarted) NODELET_WARN("horizon time went backwards (a looped bag?): the attitude filter starts over");
  if (update.outcome == AttitudeFilter::Outcome::kJump) {
    NODELET_WARN_THROTTLE(5.0, "ignoring a horizon that jumps more than attitude_max_jump_deg from the predicted attitude");
  }
  if (!update.valid) {
    if (use_horizon_) {
      NODELET_WARN_THROTTLE(5.0, "no camera attitude: no usable horizon (found, confidence >= horizon_min_confidence) "
                            "for attitude_max_hold_s; obstacles wait until the horizon is seen again");
    }
    return;
  }
  if (use_horizon_) {
    // tf carries the attitudes of accepted horizons only, as the obstacles use them (a rejected
    // horizon's extrapolated one is in the attitude topics, with confidence 0).
    if (update.recorded) broadcastPose(msg->header, update.attitude.roll, update.attitude.pitch);
    placePendingBlobs();
  }
  publishAttitude(msg->header, update.attitude);
}

void GroundProjectorNodelet::broadcastPose(const std_msgs::Header& header, double roll, double pitch) {
  double height_m;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    height_m = ground_options_.camera_height_m;
  }
  if (publish_optical_tf_ && !optical_tf_sent_ && !header.frame_id.empty()) {
    geometry_msgs::TransformStamped optical;
    optical.header.stamp = header.stamp;
    optical.header.frame_id = camera_frame_;
    optical.child_frame_id = header.frame_id;
    optical.transform.rotation = rollPitchYawToMsg(-M_PI / 2, 0, -M_PI / 2);  // REP 103: optical x right, y down, z forward
    static_broadcaster_->sendTransform(optical);
    optical_tf_sent_ = true;
  }
  geometry_msgs::TransformStamped pose;
  pose.header.stamp = header.stamp;
  pose.header.frame_id = base_frame_;
  pose.child_frame_id = camera_frame_;
  pose.transform.translation.z = height_m;
  pose.transform.rotation = rollPitchYawToMsg(roll, pitch, 0.0);  // yaw is not observable from the horizon
  tf_broadcaster_->sendTransform(pose);
}

void GroundProjectorNodelet::publishAttitude(const std_msgs::Header& header, const AttitudeTimeline::Attitude& a) {
  if (pub_attitude_.getNumSubscribers() == 0 && pub_attitude_imu_.getNumSubscribers() == 0) return;
  double stddev;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    stddev = ground_options_.attitude_stddev_deg * M_PI / 180;
  }
  geometry_msgs::QuaternionStamped attitude;
  attitude.header.stamp = header.stamp;
  attitude.header.frame_id = base_frame_;
  attitude.quaternion = rollPitchYawToMsg(a.roll, a.pitch, 0.0);
  pub_attitude_.publish(attitude);
  pub_attitude_imu_.publish(attitudeImuMsg(attitude, camera_frame_, stddev, a.confidence));
}

void GroundProjectorNodelet::blobsDroppedCb(const BlobArrayConstPtr& msg,
                                            tf2_ros::filter_failure_reasons::FilterFailureReason reason) {
  stats_.addDrop();
  const char* why = reason == tf2_ros::filter_failure_reasons::EmptyFrameID
                        ? "the blobs carry no frame_id (the camera's images must set header.frame_id)"
                        : "no transform arrived in time";
  NODELET_WARN_THROTTLE(5.0, "dropping blobs of %.3f: %s from '%s' to '%s'. Is the robot's tf running "
                        "(robot_state_publisher), or use attitude_source: horizon.",
                        msg->header.stamp.toSec(), why, msg->header.frame_id.c_str(), base_frame_.c_str());
}

void GroundProjectorNodelet::warnIfStuck() {
  const double waited_s = pose_wait_.overdueS(ros::WallTime::now().toSec());
  if (waited_s <= 0) return;
  std::string frame;
  {
    std::lock_guard<std::mutex> lock(blob_frame_mutex_);
    frame = blob_frame_;
  }
  NODELET_WARN_THROTTLE(5.0, "no transform from '%s' to '%s': blobs have waited %.1f s for their camera pose. Is "
                        "the robot's tf running (robot_state_publisher), or use attitude_source: horizon.",
                        frame.c_str(), base_frame_.c_str(), waited_s);
}

void GroundProjectorNodelet::blobsWithTfCb(const BlobArrayConstPtr& msg) {
  pose_wait_.handled();
  Eigen::Isometry3d base_from_optical;
  try {
    base_from_optical = tf2::transformToEigen(
        tf_buffer_->lookupTransform(base_frame_, msg->header.frame_id, msg->header.stamp));
  } catch (const tf2::TransformException& e) {  // the filter said it exists; it may have expired since
    NODELET_WARN_THROTTLE(5.0, "no camera pose for the blobs: %s", e.what());
    return;
  }
  place(*msg, base_from_optical);
}

void GroundProjectorNodelet::blobsWithHorizonCb(const BlobArrayConstPtr& msg) {
  {
    std::lock_guard<std::mutex> lock(attitude_mutex_);
    pending_blobs_.push_back(msg);
  }
  placePendingBlobs();
}

void GroundProjectorNodelet::placePendingBlobs() {
  // Blobs in stamp order, each at the attitude of its own stamp; those newer than the last
  // horizon wait for the next one (at most queue_size_ of them).
  for (;;) {
    BlobArrayConstPtr msg;
    double roll = 0, pitch = 0, height_m = 0;
    AttitudeTimeline::Lookup lookup;
    {
      std::lock_guard<std::mutex> lock(attitude_mutex_);
      if (pending_blobs_.empty()) return;
      msg = pending_blobs_.front();
      lookup = attitude_.attitudeAt(msg->header.stamp.toSec(), &roll, &pitch);
      if (lookup == AttitudeTimeline::Lookup::kNotYet && static_cast<int>(pending_blobs_.size()) <= queue_size_) return;
      pending_blobs_.pop_front();
    }
    if (lookup != AttitudeTimeline::Lookup::kFound) {
      stats_.addDrop();
      NODELET_WARN_THROTTLE(5.0, "dropping blobs of %.3f: no camera attitude from the horizon at that time (the "
                            "horizon must be found: is the landmark node running and the horizon in view? Or the "
                            "horizons around it are more than attitude_max_gap_s apart: the landmark node is "
                            "falling behind on a loaded CPU)",
                            msg->header.stamp.toSec());
      continue;
    }
    {
      std::lock_guard<std::mutex> lock(config_mutex_);
      height_m = ground_options_.camera_height_m;
    }
    place(*msg, baseFromOptical(roll, pitch, 0.0, height_m));
  }
}

bool GroundProjectorNodelet::fieldEdgePose(const std_msgs::Header& header, Eigen::Isometry3d* base_from_optical) {
  if (!use_horizon_) {
    try {  // the message filter waited for it; it may have expired since
      *base_from_optical = tf2::transformToEigen(tf_buffer_->lookupTransform(base_frame_, header.frame_id, header.stamp));
      return true;
    } catch (const tf2::TransformException& e) {
      NODELET_WARN_THROTTLE(5.0, "no camera pose for the field boundary: %s", e.what());
      return false;
    }
  }
  double roll = 0, pitch = 0, height_m = 0;
  {
    std::lock_guard<std::mutex> lock(attitude_mutex_);
    if (attitude_.attitudeAt(header.stamp.toSec(), &roll, &pitch) != AttitudeTimeline::Lookup::kFound) return false;
  }
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    height_m = ground_options_.camera_height_m;
  }
  *base_from_optical = baseFromOptical(roll, pitch, 0.0, height_m);
  return true;
}

bool GroundProjectorNodelet::fieldEdgeIntrinsics(CameraIntrinsics* intrinsics) {
  sensor_msgs::CameraInfoConstPtr info;
  {
    std::lock_guard<std::mutex> lock(info_mutex_);
    info = camera_info_;
  }
  std::string problem = "no camera_info yet on " + getNodeHandle().resolveName("camera_info");
  if (info && intrinsicsFromInfo(*info, intrinsics, &problem)) return true;
  NODELET_WARN_THROTTLE(5.0, "cannot place the field boundary on the ground: %s", problem.c_str());
  return false;
}

void GroundProjectorNodelet::place(const BlobArray& msg, const Eigen::Isometry3d& base_from_optical) {
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
  if (msg.image_width != 0 && (msg.image_width != info->width || msg.image_height != info->height)) {
    NODELET_ERROR_THROTTLE(5.0, "blobs come from %ux%u images but camera_info is %ux%u: not placing them "
                           "(binning or ROI? publish the matching camera_info)",
                           msg.image_width, msg.image_height, info->width, info->height);
    return;
  }
  double max_range_m;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    max_range_m = ground_options_.max_range_m;
  }
  auto out = boost::make_shared<ObstacleArray>();
  out->header.stamp = msg.header.stamp;
  out->header.frame_id = base_frame_;
  std::vector<BlobOutline> outlines;
  for (const Blob& blob : msg.blobs) outlines.push_back(outlineFromBlob(blob));
  for (size_t i = 0; i < outlines.size(); ++i) {
    GroundObstacle obstacle;
    // Above the horizon or too far: not an obstacle on the ground.
    if (!projectBlobToGround(intrinsics, base_from_optical, outlines[i], max_range_m, &obstacle)) continue;
    out->obstacles.push_back(obstacleToMsg(msg.blobs[i], obstacle, contactMayBeHidden(outlines, i)));
  }
  pub_obstacles_.publish(out);
  if (pub_markers_.getNumSubscribers() > 0) pub_markers_.publish(obstacleMarkers(*out, display_rgb_));
  stats_.addFrame(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                  threadCpuMs() - cpu_start_ms);
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::GroundProjectorNodelet, nodelet::Nodelet)
