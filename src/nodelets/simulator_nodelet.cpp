// rle_vision/Simulator: publishes the simulated biped camera view with exact ground truth.
// Frame n shows the scene at time n / rate_hz, so its content never depends on timing; the
// stamps come from ros::Time::now() and follow /clock under use_sim_time.
#include <atomic>
#include <chrono>
#include <memory>

#include <cv_bridge/cv_bridge.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TransformStamped.h>
#include <image_transport/image_transport.h>
#include <opencv2/imgproc.hpp>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <ros/ros.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include "image_conversions.h"
#include "landmark_conversions.h"
#include "processing_stats.h"
#include "rle_vision/SceneTruth.h"
#include "rle_vision/color/color_convert.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"

namespace rle_vision {

class SimulatorNodelet : public nodelet::Nodelet {
 private:
  void onInit() override;
  void scheduleFirstFrame(ros::NodeHandle& pnh);
  void timerCb(const ros::TimerEvent&);
  sensor_msgs::CameraInfo cameraInfo(const std_msgs::Header& header) const;
  SceneTruth truthMsg(const SimFrame& frame, const std_msgs::Header& header) const;
  void publishTransforms(const SimFrame& frame, const ros::Time& stamp);

  std::unique_ptr<SceneSimulator> simulator_;
  std::shared_ptr<image_transport::ImageTransport> it_;
  image_transport::CameraPublisher pub_camera_;
  image_transport::Publisher pub_labels_;
  ros::Publisher pub_truth_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  ros::Timer timer_;
  ros::WallTimer start_timer_;
  ros::WallTimer subscribers_timer_;

  double rate_hz_ = 30;
  int max_frames_ = 0;
  bool publish_tf_ = true;
  std::string encoding_ = "bgr8";
  std::string optical_frame_, camera_frame_, base_frame_;
  std::atomic<uint64_t> frame_index_{0};  // read by the diagnostics timer too

  std::shared_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  ProcessingStats stats_;  // rendering and publishing time per frame
};

void SimulatorNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  std::string scene_file;
  pnh.param<std::string>("scene_file", scene_file, ros::package::getPath("rle_vision") + "/config/scene_default.yaml");
  pnh.param("rate_hz", rate_hz_, 30.0);
  pnh.param("max_frames", max_frames_, 0);
  pnh.param("publish_tf", publish_tf_, true);
  pnh.param<std::string>("encoding", encoding_, "bgr8");
  pnh.param<std::string>("frame_id", optical_frame_, "camera_optical_frame");
  pnh.param<std::string>("camera_frame", camera_frame_, "camera_link");
  pnh.param<std::string>("base_frame", base_frame_, "base_link");
  int queue_size = 2;  // a camera's: a slow reader gets the newest frames, not old ones
  pnh.param("queue_size", queue_size, 2);
  if (!std::isfinite(rate_hz_) || rate_hz_ <= 0 || rate_hz_ > 1000) {
    NODELET_FATAL("~rate_hz must be in (0, 1000], got %f", rate_hz_);
    throw std::invalid_argument("bad ~rate_hz");
  }
  if (encoding_ != "bgr8" && encoding_ != "rgb8" && encoding_ != "mono8" && encoding_ != "yuv422") {
    NODELET_FATAL("~encoding '%s' is not supported; use bgr8, rgb8, mono8 or yuv422", encoding_.c_str());
    throw std::invalid_argument("bad ~encoding");
  }
  if (queue_size < 1) {
    NODELET_WARN("~queue_size must be >= 1, got %d: using 2", queue_size);
    queue_size = 2;
  }
  SceneConfig scene;
  try {
    scene = loadSceneConfig(scene_file);
    if (pnh.hasParam("seed")) {  // a launch-file override, e.g. for repeatable tests
      int seed = 0;
      pnh.getParam("seed", seed);
      scene.seed = static_cast<uint64_t>(seed);
    }
    double noise_sigma = -1;  // a launch-file override: a noisier or cleaner camera
    pnh.param("noise_sigma", noise_sigma, -1.0);
    if (std::isfinite(noise_sigma) && noise_sigma >= 0) scene.noise_sigma = noise_sigma;
    simulator_ = std::make_unique<SceneSimulator>(scene);
  } catch (const std::exception& e) {
    NODELET_FATAL("cannot load the scene: %s", e.what());
    throw;
  }
  NODELET_INFO("simulating %s: %dx%d %s at %.1f Hz, %zu boxes, sensor noise sigma %.1f", scene_file.c_str(),
               scene.width, scene.height, encoding_.c_str(), rate_hz_, scene.boxes.size(), scene.noise_sigma);

  it_ = std::make_shared<image_transport::ImageTransport>(nh);
  pub_camera_ = it_->advertiseCamera("image_raw", static_cast<uint32_t>(queue_size));
  pub_labels_ = it_->advertise("ground_truth/labels", static_cast<uint32_t>(queue_size));
  pub_truth_ = nh.advertise<SceneTruth>("ground_truth/scene", 10);

  if (publish_tf_) {  // optical frame: x right, y down, z forward (REP 103)
    geometry_msgs::TransformStamped optical;
    optical.header.stamp = ros::Time::now();
    optical.header.frame_id = camera_frame_;
    optical.child_frame_id = optical_frame_;
    tf2::Quaternion q;
    q.setRPY(-M_PI / 2, 0, -M_PI / 2);
    optical.transform.rotation.x = q.x();
    optical.transform.rotation.y = q.y();
    optical.transform.rotation.z = q.z();
    optical.transform.rotation.w = q.w();
    static_broadcaster_.sendTransform(optical);
  }
  diagnostics_ = std::make_shared<diagnostic_updater::Updater>(nh, pnh, getName());
  diagnostics_->setHardwareID("simulated camera");
  diagnostics_->add("simulator", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    stats_.report(s, 1000.0 / rate_hz_);
    s.add("frames published", frame_index_.load());
  });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });
  scheduleFirstFrame(pnh);
}

// Waiting lets recorders and lazily subscribing pipelines connect before frame 0: first for the
// given number of image_raw subscribers (however long a loaded machine takes to start them),
// then start_delay_s.
void SimulatorNodelet::scheduleFirstFrame(ros::NodeHandle& pnh) {
  double start_delay_s = 0;
  pnh.param("start_delay_s", start_delay_s, 0.0);
  if (!std::isfinite(start_delay_s) || start_delay_s < 0) {
    NODELET_WARN("~start_delay_s must be a number >= 0, got %f: starting at once", start_delay_s);
    start_delay_s = 0;
  }
  int start_after_subscribers = 0;
  pnh.param("start_after_subscribers", start_after_subscribers, 0);
  if (start_after_subscribers < 0) {
    NODELET_WARN("~start_after_subscribers must be >= 0, got %d: not waiting for subscribers", start_after_subscribers);
    start_after_subscribers = 0;
  }
  const auto start = [this, start_delay_s] {
    start_timer_ = getNodeHandle().createWallTimer(ros::WallDuration(std::max(start_delay_s, 1e-3)),
        [this](const ros::WallTimerEvent&) {
          timer_ = getNodeHandle().createTimer(ros::Duration(1.0 / rate_hz_), &SimulatorNodelet::timerCb, this);
        }, /*oneshot=*/true);
  };
  if (start_after_subscribers == 0) {
    start();
    return;
  }
  NODELET_INFO("frame 0 waits for %d image_raw subscribers", start_after_subscribers);
  subscribers_timer_ = getNodeHandle().createWallTimer(ros::WallDuration(0.05),
      [this, start, start_after_subscribers](const ros::WallTimerEvent&) {
        if (static_cast<int>(pub_camera_.getNumSubscribers()) < start_after_subscribers) return;
        subscribers_timer_.stop();
        start();
      });
}

sensor_msgs::CameraInfo SimulatorNodelet::cameraInfo(const std_msgs::Header& header) const {
  const PinholeCamera& c = simulator_->camera();
  sensor_msgs::CameraInfo info;
  info.header = header;
  info.width = static_cast<uint32_t>(c.width);
  info.height = static_cast<uint32_t>(c.height);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {c.fx, 0, c.cx, 0, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  return info;
}

SceneTruth SimulatorNodelet::truthMsg(const SimFrame& frame, const std_msgs::Header& header) const {
  SceneTruth truth;
  truth.header = header;
  truth.frame_index = static_cast<uint32_t>(frame.frame_index);
  for (const BoxTruth& box : frame.boxes) {
    ObjectTruth o;
    o.name = box.name;
    o.color = box.color_class;
    o.label = box.label;
    o.area = box.area;
    o.cx = static_cast<float>(box.cx);
    o.cy = static_cast<float>(box.cy);
    o.left = static_cast<uint32_t>(std::max(0, box.left));
    o.top = static_cast<uint32_t>(std::max(0, box.top));
    o.right = static_cast<uint32_t>(std::max(0, box.right));
    o.bottom = static_cast<uint32_t>(std::max(0, box.bottom));
    o.pieces = static_cast<uint32_t>(box.pieces);
    o.touches_same_color = box.touches_same_class;
    o.touches_other_box = box.touches_other_box;
    o.position.x = box.position_m.x();
    o.position.y = box.position_m.y();
    o.width_m = static_cast<float>(box.width_m);
    o.depth_m = static_cast<float>(box.depth_m);
    o.yaw_rad = static_cast<float>(box.yaw_rad);
    o.height_m = static_cast<float>(box.height_m);
    truth.objects.push_back(o);
  }
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  if (frame.horizon_visible) {
    clipLineToImage(frame.horizon, frame.image.cols, frame.image.rows, &x1, &y1, &x2, &y2);
  }
  truth.horizon = lineToMsg(frame.horizon, x1, y1, x2, y2, 0, 0);
  truth.horizon_visible = frame.horizon_visible;
  for (const EdgeTruth& e : frame.edges) {
    truth.edges.push_back(lineToMsg(lineThroughPoints(e.x1, e.y1, e.x2, e.y2), e.x1, e.y1, e.x2, e.y2, 0, 0));
  }
  truth.camera_roll = static_cast<float>(frame.pose.roll);
  truth.camera_pitch = static_cast<float>(frame.pose.pitch);
  truth.camera_yaw = static_cast<float>(frame.pose.yaw);
  truth.camera_height_m = static_cast<float>(frame.pose.height_m);
  truth.light_gain = static_cast<float>(frame.light_gain);
  return truth;
}

void SimulatorNodelet::publishTransforms(const SimFrame& frame, const ros::Time& stamp) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = base_frame_;
  t.child_frame_id = camera_frame_;
  t.transform.translation.x = frame.pose.x_m;
  t.transform.translation.y = frame.pose.y_m;
  t.transform.translation.z = frame.pose.height_m;
  tf2::Quaternion q;
  q.setRPY(frame.pose.roll, frame.pose.pitch, frame.pose.yaw);  // = Rz(yaw) Ry(pitch) Rx(roll)
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  tf_broadcaster_.sendTransform(t);
}

void SimulatorNodelet::timerCb(const ros::TimerEvent&) {
  if (max_frames_ > 0 && frame_index_ >= static_cast<uint64_t>(max_frames_)) {
    timer_.stop();
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = threadCpuMs();
  const SimFrame frame = simulator_->render(frame_index_, frame_index_ / rate_hz_);
  ++frame_index_;
  std_msgs::Header header;
  header.frame_id = optical_frame_;
  header.seq = static_cast<uint32_t>(frame.frame_index);
  sensor_msgs::ImagePtr image;
  if (encoding_ == "bgr8") {
    image = cv_bridge::CvImage(header, "bgr8", frame.image).toImageMsg();
  } else if (encoding_ == "rgb8") {
    image = cv_bridge::CvImage(header, "rgb8", convertBgrImage(frame.image, ColorSpace::RGB)).toImageMsg();
  } else if (encoding_ == "mono8") {
    cv::Mat gray;
    cv::cvtColor(frame.image, gray, cv::COLOR_BGR2GRAY);
    image = cv_bridge::CvImage(header, "mono8", gray).toImageMsg();
  } else {  // yuv422 (UYVY)
    image = cv_bridge::CvImage(header, "yuv422", bgrToUyvy(frame.image)).toImageMsg();
  }
  // Stamped when the frame is ready, as a camera driver stamps at capture, and published at
  // once (the tracker's latency counts from the stamp); tf and ground truth follow.
  header.stamp = ros::Time::now();
  image->header = header;
  pub_camera_.publish(image, boost::make_shared<sensor_msgs::CameraInfo>(cameraInfo(header)));
  if (publish_tf_) publishTransforms(frame, header.stamp);
  pub_truth_.publish(truthMsg(frame, header));
  if (pub_labels_.getNumSubscribers() > 0) {
    pub_labels_.publish(cv_bridge::CvImage(header, "mono8", frame.labels).toImageMsg());
  }
  stats_.addFrame(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                  threadCpuMs() - cpu_start_ms);
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::SimulatorNodelet, nodelet::Nodelet)
