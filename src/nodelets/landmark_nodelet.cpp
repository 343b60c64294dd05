// rle_vision/Landmark: the low-priority landmark node. Edge images go into a one-slot mailbox
// (a newer frame replaces an unprocessed one, which counts as dropped); a worker thread at low
// OS priority runs the RLE Hough and the horizon and publishes lines, horizon, rviz markers
// and a debug overlay, and (learning on) measures the colours of the objects the lines bound
// and publishes updated colour ranges for the tracker. It never queues frames and never holds
// up the manager's other nodelets (the tracker).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>

#include <cv_bridge/cv_bridge.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.h"
#include "error_throttle.h"
#include "low_priority_worker.h"
#include "processing_stats.h"
#include "startup_params.h"
#include "rle_vision/ColorRangeArray.h"
#include "rle_vision/Horizon.h"
#include "rle_vision/LandmarkConfig.h"
#include "rle_vision/LineArray.h"
#include "rle_vision/color_table.h"
#include "rle_vision/config_files.h"
#include "rle_vision/landmark_detector.h"
#include "rle_vision/overlay.h"

namespace rle_vision {

namespace {

geometry_msgs::Point backProject(const PinholeCamera& camera, double u, double v) {
  // The ray through (u, v) at 1 m depth in the optical frame: rviz's camera view overlays it
  // on the pixel.
  geometry_msgs::Point p;
  p.x = (u - camera.cx) / camera.fx;
  p.y = (v - camera.cy) / camera.fy;
  p.z = 1.0;
  return p;
}

}  // namespace

class LandmarkNodelet : public nodelet::Nodelet {
 public:
  ~LandmarkNodelet() override;

 private:
  void onInit() override;
  void connectCb();
  void edgesCb(const sensor_msgs::ImageConstPtr& msg);
  void imageCb(const sensor_msgs::ImageConstPtr& msg);
  void cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg);
  void reconfigureCb(LandmarkConfig& config, uint32_t level);
  void process(const sensor_msgs::ImageConstPtr& edges_msg);
  void publishMarkers(const std_msgs::Header& header, const LandmarkResult& result, const PinholeCamera& camera);
  void learn(const std_msgs::Header& header, const cv::Mat& bgr, const LandmarkResult& result, bool learning,
             const LearningOptions& options);
  void publishRanges(const std_msgs::Header& header, const std::vector<ColorClass>& classes);

  std::shared_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber sub_edges_, sub_image_;
  ros::Subscriber sub_info_;
  ros::Subscriber sub_resume_;
  ros::Publisher pub_lines_, pub_horizon_, pub_markers_, pub_ranges_;
  image_transport::Publisher pub_debug_;
  std::mutex connect_mutex_;
  bool low_priority_ = true;

  std::mutex config_mutex_;
  LandmarkOptions options_;
  bool learning_ = true;
  LearningOptions learning_options_;
  double publish_period_s_ = 0.5;
  std::shared_ptr<dynamic_reconfigure::Server<LandmarkConfig>> reconfigure_server_;
  std::unique_ptr<LandmarkConfig> accepted_config_;  // shown again when a new one is refused

  // Latest camera_info and recent colour images (for pitch, markers, learning, the overlay);
  // an edge image is paired with the colour image of the same stamp.
  std::mutex inputs_mutex_;
  // Learned ranges to resume from (the tracker's active ones at start-up), for the worker.
  std::unique_ptr<std::vector<ColorClass>> pending_resume_;
  std::atomic<bool> resume_taken_{false};
  sensor_msgs::CameraInfoConstPtr camera_info_;
  std::deque<sensor_msgs::ImageConstPtr> colours_;

  // The one-slot mailbox and its worker.
  LowPriorityWorker worker_;
  std::atomic<bool> warned_no_camera_info_{false};

  std::shared_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  ProcessingStats stats_;
  ErrorThrottle input_errors_;  // bad input, per kind of problem
  // For diagnostics (written by the worker): when color_ranges went out last (wall s, 0: never).
  std::atomic<double> ranges_published_s_{0};
  std::atomic<int> learned_classes_{0};
  std::atomic<bool> learning_enabled_{true};

  // Used by the worker only.
  LandmarkDetector detector_;
  std::vector<ColorClass> configured_classes_;
  std::unique_ptr<ColorLearner> learner_;
  bool published_learned_ = false, ranges_pending_ = false;
  ros::WallTime last_ranges_publish_;
  cv::Mat bgr_;
};

LandmarkNodelet::~LandmarkNodelet() {
  worker_.stop();
}

void LandmarkNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_shared<image_transport::ImageTransport>(nh);
  pnh.param("low_priority", low_priority_, true);
  std::string colors_file;
  pnh.param<std::string>("colors_file", colors_file, ros::package::getPath("rle_vision") + "/config/colors.yaml");
  try {
    configured_classes_ = loadColorClasses(colors_file);
  } catch (const std::exception& e) {
    NODELET_FATAL("cannot load colour classes for learning: %s. Set ~colors_file (the tracker's file).", e.what());
    throw;
  }
  learner_ = std::make_unique<ColorLearner>(configured_classes_, LearningOptions());
  for (const std::string& problem : startupParamProblems<LandmarkConfig>(pnh)) NODELET_WARN("%s", problem.c_str());
  reconfigure_server_ = std::make_shared<dynamic_reconfigure::Server<LandmarkConfig>>(pnh);
  reconfigure_server_->setCallback([this](LandmarkConfig& config, uint32_t level) { reconfigureCb(config, level); });

  diagnostics_ = std::make_shared<diagnostic_updater::Updater>(nh, pnh, getName());
  diagnostics_->setHardwareID("none");
  diagnostics_->add("landmark", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    stats_.report(s, 30.0);
    s.add("colour learning", learning_enabled_.load() ? "on" : "off");
    s.add("learned colour classes", learned_classes_.load());
    const double published = ranges_published_s_.load();
    s.add("colour ranges age (s)", published > 0 ? ros::WallTime::now().toSec() - published : -1.0);
  });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });

  worker_.start(
      low_priority_, [this](const sensor_msgs::ImageConstPtr& msg) { process(msg); },
      [this](bool niced, bool idled) {
        if (low_priority_) {
          NODELET_INFO("landmark worker runs at low priority (nice 19: %s, SCHED_IDLE: %s)", niced ? "yes" : "no",
                       idled ? "yes" : "no");
        }
      },
      [this](const char* what) { NODELET_ERROR_THROTTLE(5.0, "landmark processing failed: %s", what); });

  std::lock_guard<std::mutex> lock(connect_mutex_);
  const ros::SubscriberStatusCallback connect_cb = [this](const ros::SingleSubscriberPublisher&) { connectCb(); };
  const image_transport::SubscriberStatusCallback image_connect_cb =
      [this](const image_transport::SingleSubscriberPublisher&) { connectCb(); };
  pub_lines_ = nh.advertise<LineArray>("lines", 5, connect_cb, connect_cb);
  pub_horizon_ = nh.advertise<Horizon>("horizon", 5, connect_cb, connect_cb);
  pub_markers_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 2, connect_cb, connect_cb);
  pub_debug_ = image_transport::ImageTransport(pnh).advertise("debug_image", 1, image_connect_cb, image_connect_cb);
  pub_ranges_ = nh.advertise<ColorRangeArray>("color_ranges", 1, connect_cb, connect_cb, ros::VoidConstPtr(), /*latch=*/true);
  sub_info_ = nh.subscribe("camera_info", 1, &LandmarkNodelet::cameraInfoCb, this);
  // A restarted landmark node continues from the learned ranges the tracker still uses (its
  // latched active ranges) instead of starting over from the configured ones.
  std::string resume_from;
  pnh.param<std::string>("resume_from", resume_from, "tracker/active_color_ranges");
  if (!resume_from.empty()) {
    const boost::function<void(const ColorRangeArrayConstPtr&)> resume_cb = [this](const ColorRangeArrayConstPtr& msg) {
      if (resume_taken_.exchange(true)) return;  // only the first message (the latched state)
      auto classes = std::make_unique<std::vector<ColorClass>>();
      std::string error;
      if (!colorClassesFromMsg(*msg, classes.get(), &error)) return;
      std::lock_guard<std::mutex> lock(inputs_mutex_);
      pending_resume_ = std::move(classes);
    };
    sub_resume_ = nh.subscribe<ColorRangeArray>(resume_from, 1, resume_cb);
  }
}

void LandmarkNodelet::reconfigureCb(LandmarkConfig& config, uint32_t /*level*/) {
  const LandmarkOptions candidate = optionsFromConfig(config);
  const LearningOptions learning = learningFromConfig(config);
  std::string problem = validateLandmarkOptions(candidate);
  if (problem.empty()) problem = validateLearningOptions(learning);
  if (problem.empty() && !std::isfinite(config.learning_publish_period_s)) problem = "learning_publish_period_s is not a number";
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    if (!problem.empty()) {
      NODELET_WARN("refusing landmark parameters: %s; keeping the previous ones", problem.c_str());
      if (accepted_config_) config = *accepted_config_;  // rqt_reconfigure shows what is in effect
      return;
    }
    accepted_config_ = std::make_unique<LandmarkConfig>(config);
    options_ = candidate;
    learning_options_ = learning;
    learning_ = config.learning;
    learning_enabled_ = config.learning;
    publish_period_s_ = config.learning_publish_period_s;
  }
  if (pub_ranges_) connectCb();  // learning on or off changes what is subscribed
}

void LandmarkNodelet::connectCb() {
  bool learning;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    learning = learning_;
  }
  std::lock_guard<std::mutex> lock(connect_mutex_);
  // Learning feeds the tracker (a color_ranges subscriber) even when nobody watches lines.
  const bool feeding = learning && pub_ranges_.getNumSubscribers() > 0;
  const bool wanted = feeding || pub_lines_.getNumSubscribers() > 0 || pub_horizon_.getNumSubscribers() > 0 ||
                      pub_markers_.getNumSubscribers() > 0 || pub_debug_.getNumSubscribers() > 0;
  if (!wanted) {
    sub_edges_.shutdown();
  } else if (!sub_edges_) {
    sub_edges_ = it_->subscribe("edges", 1, &LandmarkNodelet::edgesCb, this);
  }
  // The colour image feeds learning and the overlay.
  if (!feeding && pub_debug_.getNumSubscribers() == 0) {
    sub_image_.shutdown();
  } else if (!sub_image_) {
    sub_image_ = it_->subscribe("image_raw", 2, &LandmarkNodelet::imageCb, this);
  }
}

void LandmarkNodelet::cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg) {
  std::lock_guard<std::mutex> lock(inputs_mutex_);
  camera_info_ = msg;
}

void LandmarkNodelet::imageCb(const sensor_msgs::ImageConstPtr& msg) {
  std::lock_guard<std::mutex> lock(inputs_mutex_);
  colours_.push_back(msg);
  while (colours_.size() > 8) colours_.pop_front();  // a few frames cover the edge detector's delay
}

void LandmarkNodelet::edgesCb(const sensor_msgs::ImageConstPtr& msg) {
  if (worker_.put(msg)) stats_.addDrop();  // the worker did not get to the previous frame
}

void LandmarkNodelet::process(const sensor_msgs::ImageConstPtr& msg) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = threadCpuMs();
  PixelFormat format;
  cv::Mat edges;
  std::string error;
  if (viewImage(*msg, &format, &edges, &error) && format != PixelFormat::MONO8) {
    error = "edge images must be mono8 (the EdgeDetector's output), got " + msg->encoding;
  }
  if (!error.empty()) {
    if (input_errors_.shouldLog(error)) {
      NODELET_ERROR("dropping edge image on %s: %s", sub_edges_.getTopic().c_str(), error.c_str());
    }
    return;
  }
  LandmarkOptions options;
  LearningOptions learning_options;
  bool learning;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    options = options_;
    learning_options = learning_options_;
    learning = learning_;
  }
  sensor_msgs::CameraInfoConstPtr info;
  sensor_msgs::ImageConstPtr colour;
  {
    std::lock_guard<std::mutex> lock(inputs_mutex_);
    info = camera_info_;
    for (const sensor_msgs::ImageConstPtr& c : colours_) {
      if (c->header.stamp == msg->header.stamp) colour = c;
    }
  }
  // The colour image of this frame, as BGR (a view when it already is).
  cv::Mat bgr;
  if (colour) {
    PixelFormat colour_format;
    cv::Mat colour_view;
    if (viewImage(*colour, &colour_format, &colour_view, &error)) {
      if (colour_format == PixelFormat::BGR8) {
        bgr = colour_view;
      } else {
        bgr_ = toDisplayBgr(colour_view, colour_format);
        bgr = bgr_;
      }
    }
  }
  PinholeCamera camera;
  const bool have_camera = info && cameraFromInfo(*info, &camera) && camera.width == edges.cols &&
                           camera.height == edges.rows;
  if (!have_camera && !warned_no_camera_info_.exchange(true)) {
    NODELET_WARN("no usable camera_info for %dx%d images on %s: horizon pitch will be NaN and markers are off",
                 edges.cols, edges.rows, sub_info_.getTopic().c_str());
  }

  LandmarkResult result;
  detector_.detectInEdges(edges, options, &result);

  auto lines = boost::make_shared<LineArray>();
  lines->header = msg->header;
  for (const DetectedLine& l : result.lines) {
    lines->lines.push_back(lineToMsg(l.line, l.x1, l.y1, l.x2, l.y2, l.votes, l.support));
  }
  auto horizon = boost::make_shared<Horizon>();
  horizon->header = msg->header;
  horizon->found = result.horizon.found;
  horizon->roll = horizon->pitch = std::numeric_limits<float>::quiet_NaN();
  if (result.horizon.found) {
    const HorizonEstimate& h = result.horizon;
    horizon->line = lineToMsg(h.line, h.x1, h.y1, h.x2, h.y2, h.votes, h.support);
    horizon->confidence = static_cast<float>(h.confidence);
    double roll = 0, pitch = 0;
    horizonAttitude(h.line, have_camera ? &camera : nullptr, &roll, &pitch);
    horizon->roll = static_cast<float>(roll);
    horizon->pitch = static_cast<float>(pitch);
  }
  lines->processing_time_ms = static_cast<float>(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  pub_lines_.publish(lines);
  pub_horizon_.publish(horizon);
  if (learning && !bgr.empty() && bgr.size() == edges.size()) {
    learn(msg->header, bgr, result, true, learning_options);
  } else if (learning) {
    NODELET_WARN_THROTTLE(10.0, "learning is on but no colour image (image_raw) of the edge image's size and stamp "
                          "arrived, so no colours are measured; image_raw and edges must come from the same camera");
  } else {
    learn(msg->header, bgr, result, false, learning_options);
  }
  if (have_camera && pub_markers_.getNumSubscribers() > 0) publishMarkers(msg->header, result, camera);
  if (pub_debug_.getNumSubscribers() > 0) {
    cv::Mat canvas;
    if (!bgr.empty()) {
      canvas = bgr.clone();
    } else {
      cv::cvtColor(edges, canvas, cv::COLOR_GRAY2BGR);
    }
    drawLandmarks(&canvas, result.lines, result.horizon, horizon->roll, horizon->pitch);
    if (learning) {
      drawLearning(&canvas, learner_->lastMeasurements());
      drawColorSwatches(&canvas, ColorTable(learner_->classes()));
    }
    pub_debug_.publish(debugImageMsg(msg->header, canvas));
  }
  stats_.addFrame(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                  threadCpuMs() - cpu_start_ms);
}

void LandmarkNodelet::learn(const std_msgs::Header& header, const cv::Mat& bgr, const LandmarkResult& result,
                            bool learning, const LearningOptions& options) {
  if (!learning) {
    // Learning switched off: hand the tracker its configured ranges back, once.
    if (published_learned_) {
      learner_ = std::make_unique<ColorLearner>(configured_classes_, options);
      publishRanges(header, configured_classes_);
      published_learned_ = false;
      ranges_pending_ = false;
    }
    return;
  }
  learner_->setOptions(options);
  std::unique_ptr<std::vector<ColorClass>> resume;
  {
    std::lock_guard<std::mutex> lock(inputs_mutex_);
    resume.swap(pending_resume_);
  }
  if (resume && !published_learned_) {
    const int resumed = learner_->resume(*resume, header.stamp.toSec());
    if (resumed > 0) {
      NODELET_INFO("resuming from %d learned colour ranges the tracker uses", resumed);
      published_learned_ = true;
    }
  }
  ranges_pending_ = learner_->update(bgr, result, detector_.edgeObjects(), header.stamp.toSec()) || ranges_pending_;
  double period;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    period = publish_period_s_;
  }
  const ros::WallTime now = ros::WallTime::now();
  if (ranges_pending_ && (last_ranges_publish_.isZero() || (now - last_ranges_publish_).toSec() >= period)) {
    publishRanges(header, learner_->classes());
    last_ranges_publish_ = now;
    published_learned_ = true;
    ranges_pending_ = false;
  }
}

void LandmarkNodelet::publishRanges(const std_msgs::Header& header, const std::vector<ColorClass>& classes) {
  auto msg = boost::make_shared<ColorRangeArray>();
  msg->header = header;
  for (const ColorClass& c : classes) msg->ranges.push_back(colorRangeToMsg(c));
  pub_ranges_.publish(msg);
  ranges_published_s_ = ros::WallTime::now().toSec();
  learned_classes_ = static_cast<int>(
      std::count_if(classes.begin(), classes.end(), [](const ColorClass& c) { return c.source == "learned"; }));
}

void LandmarkNodelet::publishMarkers(const std_msgs::Header& header, const LandmarkResult& result,
                                     const PinholeCamera& camera) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker lines;
  lines.header = header;
  lines.ns = "lines";
  lines.id = 0;
  lines.type = visualization_msgs::Marker::LINE_LIST;
  lines.action = visualization_msgs::Marker::ADD;
  lines.pose.orientation.w = 1.0;
  lines.scale.x = 0.003;
  lines.color.g = 1.0;
  lines.color.a = 1.0;
  for (const DetectedLine& l : result.lines) {
    lines.points.push_back(backProject(camera, l.x1, l.y1));
    lines.points.push_back(backProject(camera, l.x2, l.y2));
  }
  if (lines.points.empty()) lines.action = visualization_msgs::Marker::DELETE;
  array.markers.push_back(lines);
  visualization_msgs::Marker horizon = lines;
  horizon.ns = "horizon";
  horizon.type = visualization_msgs::Marker::LINE_STRIP;
  horizon.scale.x = 0.008;
  horizon.color.r = 0.0;
  horizon.color.g = 1.0;
  horizon.color.b = 1.0;
  horizon.points.clear();
  horizon.action = visualization_msgs::Marker::DELETE;
  if (result.horizon.found) {
    horizon.action = visualization_msgs::Marker::ADD;
    horizon.points.push_back(backProject(camera, result.horizon.x1, result.horizon.y1));
    horizon.points.push_back(backProject(camera, result.horizon.x2, result.horizon.y2));
  }
  array.markers.push_back(horizon);
  pub_markers_.publish(array);
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::LandmarkNodelet, nodelet::Nodelet)
