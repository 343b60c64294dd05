// rle_vision/Landmark: the low-priority landmark node. Edge images go into a one-slot mailbox
// (a newer frame replaces an unprocessed one, which counts as dropped); a worker thread at low
// OS priority runs the core's landmark detector and colour-learning loop on them and publishes
// lines, horizon, rviz markers, a debug overlay and (learning on) the colour ranges for the
// tracker. It never queues frames and never holds up the manager's other nodelets (the tracker).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <message_filters/cache.h>
#include <nodelet/nodelet.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "color_range_conversions.h"
#include "error_throttle.h"
#include "field_conversions.h"
#include "node_settings.h"
#include "rle_vision/io/horizon_model_file.h"
#include "image_conversions.h"
#include "landmark_conversions.h"
#include "landmark_markers.h"
#include "low_priority_worker.h"
#include "processing_stats.h"
#include "startup_params.h"
#include "rle_vision/LineArray.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/learning/color_learning_loop.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/field/field_detector.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/color/color_convert.h"
#include "rle_vision/pipeline/overlay.h"
#include "rle_vision/common/startup_wait.h"

namespace rle_vision {

// What the Landmark node reads once at start: the RLE_LANDMARK_SETTING lines of its table.
struct LandmarkSettings {
#define RLE_LANDMARK_SETTING(key, type, default_value, min, max, description) type key = default_value;
#include "rle_vision/params/landmark_params.def"
};

class LandmarkNodelet : public nodelet::Nodelet {
 public:
  ~LandmarkNodelet() override { worker_.stop(); }

 private:
  // The parameters in effect, copied under the mutex for each frame.
  struct Settings {
    LandmarkOptions landmark;
    LearningOptions learning;
    LearningLoopOptions loop;
    FieldOptions field;
  };

  void onInit() override;
  void readStartupSettings(const ros::NodeHandle& pnh);
  void advertiseAndSubscribe(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  void connectCb();
  void edgesCb(const sensor_msgs::ImageConstPtr& msg);
  void imageCb(const sensor_msgs::ImageConstPtr& msg);
  void cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg);
  void reconfigureCb(LandmarkConfig& config, uint32_t level);
  Settings settings();
  void process(const sensor_msgs::ImageConstPtr& edges_msg);
  bool viewEdges(const sensor_msgs::ImageConstPtr& msg, cv::Mat* edges);
  // The colour image of the edge image's stamp, as BGR. A view into *colour_msg's data when it
  // already is BGR: the caller keeps *colour_msg (the pixels) for as long as it uses the view.
  cv::Mat colourImage(const sensor_msgs::Image& edges_msg, const cv::Size& size, sensor_msgs::ImageConstPtr* colour_msg);
  sensor_msgs::ImageConstPtr waitForColour(const ros::Time& stamp);
  bool camera(const cv::Size& size, PinholeCamera* camera);
  void noteMissingColour(const std_msgs::Header& header, const cv::Size& size);
  void reportBudget(diagnostic_updater::DiagnosticStatusWrapper& status);
  FieldResult publishField(const std_msgs::Header& header, const cv::Mat& bgr, const Settings& settings);
  void learnColours(const std_msgs::Header& header, const cv::Mat& bgr, const LandmarkResult& result,
                    const FieldColor& field, const Settings& settings);
  void publishRanges(const std_msgs::Header& header, const std::vector<ColorClass>& classes);
  void publishDebug(const std_msgs::Header& header, const cv::Mat& bgr, const cv::Mat& edges,
                    const LandmarkResult& result, const Horizon& horizon, const FieldBoundaryEstimate& field,
                    bool learning);

  std::shared_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber sub_edges_, sub_image_;
  std::string edges_topic_;  // for the worker's log messages: connectCb may replace sub_edges_
  ros::Subscriber sub_info_, sub_resume_;
  ros::Publisher pub_lines_, pub_horizon_, pub_field_, pub_markers_, pub_ranges_;
  image_transport::Publisher pub_debug_;
  std::mutex connect_mutex_;
  LandmarkSettings startup_;  // read once at start
  HorizonModel horizon_model_;  // from startup_.horizon_model_file

  std::mutex config_mutex_;
  Settings settings_;
  std::shared_ptr<dynamic_reconfigure::Server<LandmarkConfig>> reconfigure_server_;
  std::unique_ptr<LandmarkConfig> accepted_config_;  // shown again when a new one is refused

  // Recent colour images, for the edge image of the same stamp (the horizon, learning and the
  // overlay). The edge image is made from its colour image, which therefore normally arrives
  // first; when it has not yet (the subscriptions just connected, a busy manager), the worker
  // waits for it: a bounded while (at start-up, or when an older colour image is the newest).
  message_filters::Cache<sensor_msgs::Image> colours_{8};
  std::mutex colour_mutex_;
  std::condition_variable colour_arrived_;
  StartupWait colour_wait_{1.0};  // the first frames wait this long (s) for any colour image
  std::mutex info_mutex_;
  std::condition_variable info_arrived_;
  sensor_msgs::CameraInfoConstPtr camera_info_;
  StartupWait camera_info_wait_{1.0};  // the first frame waits this long (s) for camera_info

  LowPriorityWorker worker_;
  std::shared_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  ProcessingStats stats_;
  ErrorThrottle input_errors_;  // bad input, per kind of problem
  // For diagnostics (written by the worker): when color_ranges went out last (wall s, 0: never).
  std::atomic<double> ranges_published_s_{0};
  std::atomic<int> learned_classes_{0};
  std::atomic<bool> learning_enabled_{true};
  std::atomic<int> frames_without_colour_{0};
  // Frames whose Hough work budget (max_refinements_per_frame) ran out: since the last report,
  // in all, and the edge objects the last such frame skipped.
  std::atomic<int> frames_over_budget_{0}, frames_over_budget_total_{0};
  std::atomic<uint64_t> objects_skipped_{0};
  // The field stage's last frame, for diagnostics.
  std::atomic<bool> field_found_{false};
  std::atomic<double> field_confidence_{0}, field_ms_{0};
  std::atomic<bool> resume_taken_{false};

  // Used by the worker only.
  LandmarkDetector detector_;
  FieldDetector field_detector_;
  std::unique_ptr<ColorLearningLoop> learning_loop_;
  bool warned_no_camera_info_ = false;
  cv::Mat bgr_;  // the colour image converted to BGR when it is not already
};

void LandmarkNodelet::readStartupSettings(const ros::NodeHandle& pnh) {
  std::vector<std::string> problems;
#define RLE_LANDMARK_SETTING(key, type, default_value, min, max, description) \
  readSetting(pnh, #key, &startup_.key, min, max, &problems);
#include "rle_vision/params/landmark_params.def"
  for (const std::string& problem : problems) NODELET_WARN("%s", problem.c_str());
  try {
    horizon_model_ = horizonModelFromSetting(startup_.horizon_model_file);
    NODELET_INFO("horizon weighed by %s", horizon_model_.valid ? "the horizon model" : "the product of the region evidence");
  } catch (const std::exception& e) {
    NODELET_ERROR("cannot read the horizon model: %s. Weighing horizons by the product of the region evidence; set "
                  "~horizon_model_file to a model made by make train-horizon, or to none", e.what());
  }
}

void LandmarkNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_shared<image_transport::ImageTransport>(nh);
  readStartupSettings(pnh);
  const std::string colors_file =
      startup_.colors_file.empty() ? ros::package::getPath("rle_vision") + "/config/colors.yaml" : startup_.colors_file;
  try {
    const std::vector<ColorClass> classes = loadColorClasses(colors_file);
    learning_loop_ = std::make_unique<ColorLearningLoop>(classes);
    for (const ColorClass& c : classes) {
      if (c.name == kFieldClassName) field_detector_.setConfiguredColour(c);  // the floor's colour seeds from it
    }
  } catch (const std::exception& e) {
    NODELET_FATAL("cannot load colour classes for learning: %s. Set ~colors_file (the tracker's file).", e.what());
    throw;
  }
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
    s.add("frames without a colour image of their stamp", frames_without_colour_.load());
    reportBudget(s);
    s.add("field boundary found (last frame)", field_found_.load() ? "yes" : "no");
    s.add("field boundary confidence (last frame)", field_confidence_.load());
    s.add("field stage time (last frame, ms)", field_ms_.load());
  });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });

  worker_.start(
      startup_.low_priority, [this](const sensor_msgs::ImageConstPtr& msg) { process(msg); },
      [this](bool niced, bool idled) {
        if (startup_.low_priority) {
          NODELET_INFO("landmark worker runs at low priority (nice 19: %s, SCHED_IDLE: %s)", niced ? "yes" : "no",
                       idled ? "yes" : "no");
        }
      },
      [this](const char* what) { NODELET_ERROR_THROTTLE(5.0, "landmark processing failed: %s", what); });
  advertiseAndSubscribe(nh, pnh);
}

void LandmarkNodelet::advertiseAndSubscribe(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  edges_topic_ = nh.resolveName("edges");
  const ros::SubscriberStatusCallback connect_cb = [this](const ros::SingleSubscriberPublisher&) { connectCb(); };
  const image_transport::SubscriberStatusCallback image_connect_cb =
      [this](const image_transport::SingleSubscriberPublisher&) { connectCb(); };
  pub_lines_ = nh.advertise<LineArray>("lines", 5, connect_cb, connect_cb);
  pub_horizon_ = nh.advertise<Horizon>("horizon", 5, connect_cb, connect_cb);
  pub_field_ = nh.advertise<FieldBoundary>("field_boundary", 5, connect_cb, connect_cb);
  pub_markers_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 2, connect_cb, connect_cb);
  pub_debug_ = image_transport::ImageTransport(pnh).advertise("debug_image", 1, image_connect_cb, image_connect_cb);
  pub_ranges_ = nh.advertise<ColorRangeArray>("color_ranges", 1, connect_cb, connect_cb, ros::VoidConstPtr(), /*latch=*/true);
  sub_info_ = nh.subscribe("camera_info", 1, &LandmarkNodelet::cameraInfoCb, this);
  // A restarted landmark node continues from the learned ranges the tracker still uses (its
  // latched active ranges) instead of starting over from the configured ones.
  const std::string& resume_from = startup_.resume_from;
  if (resume_from.empty()) return;
  const boost::function<void(const ColorRangeArrayConstPtr&)> resume_cb = [this](const ColorRangeArrayConstPtr& msg) {
    if (resume_taken_.exchange(true)) return;  // only the first message (the latched state)
    std::vector<ColorClass> classes;
    std::string error;
    if (colorClassesFromMsg(*msg, &classes, &error)) learning_loop_->offerResume(std::move(classes));
  };
  sub_resume_ = nh.subscribe<ColorRangeArray>(resume_from, 1, resume_cb);
}

void LandmarkNodelet::reconfigureCb(LandmarkConfig& config, uint32_t /*level*/) {
  Settings candidate{optionsFromConfig(config), learningFromConfig(config), learningLoopFromConfig(config),
                     fieldFromConfig(config)};
  candidate.landmark.horizon.model = horizon_model_;
  std::string problem = validateLandmarkOptions(candidate.landmark);
  if (problem.empty()) problem = validateLearningOptions(candidate.learning);
  if (problem.empty()) problem = validateLearningLoopOptions(candidate.loop);
  if (problem.empty()) problem = validateFieldOptions(candidate.field);
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    if (!problem.empty()) {
      NODELET_WARN("refusing landmark parameters: %s; keeping the previous ones", problem.c_str());
      if (accepted_config_) config = *accepted_config_;  // rqt_reconfigure shows what is in effect
      return;
    }
    accepted_config_ = std::make_unique<LandmarkConfig>(config);
    settings_ = candidate;
    learning_enabled_ = candidate.loop.enabled;
  }
  if (pub_ranges_) connectCb();  // learning on or off changes what is subscribed
}

LandmarkNodelet::Settings LandmarkNodelet::settings() {
  std::lock_guard<std::mutex> lock(config_mutex_);
  return settings_;
}

void LandmarkNodelet::connectCb() {
  const bool learning = settings().loop.enabled;
  std::lock_guard<std::mutex> lock(connect_mutex_);
  // Learning feeds the tracker (a color_ranges subscriber) even when nobody watches lines.
  const bool feeding = learning && pub_ranges_.getNumSubscribers() > 0;
  const bool wanted = feeding || pub_lines_.getNumSubscribers() > 0 || pub_horizon_.getNumSubscribers() > 0 ||
                      pub_field_.getNumSubscribers() > 0 ||
                      pub_markers_.getNumSubscribers() > 0 || pub_debug_.getNumSubscribers() > 0;
  // The colour image of each edge image feeds the horizon's region evidence, learning and
  // the overlay.
  if (!wanted) {
    sub_edges_.shutdown();
    sub_image_.shutdown();
    return;
  }
  if (!sub_edges_) sub_edges_ = it_->subscribe("edges", 1, &LandmarkNodelet::edgesCb, this);
  if (!sub_image_) sub_image_ = it_->subscribe("image_raw", 2, &LandmarkNodelet::imageCb, this);
}

void LandmarkNodelet::cameraInfoCb(const sensor_msgs::CameraInfoConstPtr& msg) {
  {
    std::lock_guard<std::mutex> lock(info_mutex_);
    camera_info_ = msg;
  }
  info_arrived_.notify_all();
}

void LandmarkNodelet::edgesCb(const sensor_msgs::ImageConstPtr& msg) {
  if (worker_.put(msg)) stats_.addDrop();  // the worker did not get to the previous frame
}

void LandmarkNodelet::process(const sensor_msgs::ImageConstPtr& msg) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = threadCpuMs();
  cv::Mat edges;
  if (!viewEdges(msg, &edges)) return;
  PinholeCamera camera_model;
  const bool have_camera = camera(edges.size(), &camera_model);
  const Settings s = settings();
  // The colour image of this stamp (the horizon's region evidence); without it this frame has
  // lines but no horizon. colour_msg holds its pixels: the cache drops its copy when newer
  // images arrive, which they do while this idle-priority thread works.
  sensor_msgs::ImageConstPtr colour_msg;
  const cv::Mat bgr = colourImage(*msg, edges.size(), &colour_msg);
  if (bgr.empty()) noteMissingColour(msg->header, edges.size());
  LandmarkResult result;
  detector_.detect(bgr, edges, s.landmark, &result);
  if (result.hough.budget_exhausted) {
    ++frames_over_budget_;
    ++frames_over_budget_total_;
    objects_skipped_ = result.hough.objects_skipped;
  }
  double roll = 0, pitch = 0;
  horizonAttitude(result.horizon.line, have_camera ? &camera_model : nullptr, &roll, &pitch);
  auto lines = boost::make_shared<LineArray>();
  lines->header = msg->header;
  for (const DetectedLine& l : result.lines) lines->lines.push_back(lineToMsg(l));
  const auto horizon = boost::make_shared<Horizon>(horizonToMsg(msg->header, result.horizon, roll, pitch));
  lines->processing_time_ms = static_cast<float>(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  pub_lines_.publish(lines);
  pub_horizon_.publish(horizon);
  const FieldResult field = publishField(msg->header, bgr, s);
  learnColours(msg->header, bgr, result, field.colour, s);
  if (have_camera && pub_markers_.getNumSubscribers() > 0) {
    pub_markers_.publish(landmarkMarkers(msg->header, result, camera_model));
  }
  if (pub_debug_.getNumSubscribers() > 0) {
    publishDebug(msg->header, bgr, edges, result, *horizon, field.boundary, s.loop.enabled);
  }
  stats_.addFrame(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                  threadCpuMs() - cpu_start_ms);
}

bool LandmarkNodelet::viewEdges(const sensor_msgs::ImageConstPtr& msg, cv::Mat* edges) {
  PixelFormat format;
  std::string error;
  if (viewImage(*msg, &format, edges, &error) && format != PixelFormat::MONO8) {
    error = "edge images must be mono8 (the EdgeDetector's output), got " + msg->encoding;
  }
  if (error.empty()) return true;
  if (input_errors_.shouldLog(error)) {
    NODELET_ERROR("dropping edge image on %s: %s", edges_topic_.c_str(), error.c_str());
  }
  return false;
}

void LandmarkNodelet::imageCb(const sensor_msgs::ImageConstPtr& msg) {
  {
    std::lock_guard<std::mutex> lock(colour_mutex_);
    colours_.add(msg);
  }
  colour_arrived_.notify_all();
}

sensor_msgs::ImageConstPtr LandmarkNodelet::waitForColour(const ros::Time& stamp) {
  constexpr double kLateColourS = 0.1;  // how long a colour image may lag its own edge image
  auto same_stamp = [this, &stamp] {
    const std::vector<sensor_msgs::ImageConstPtr> found = colours_.getInterval(stamp, stamp);
    return found.empty() ? sensor_msgs::ImageConstPtr() : found.back();
  };
  std::unique_lock<std::mutex> lock(colour_mutex_);
  sensor_msgs::ImageConstPtr colour = same_stamp();
  if (colour) return colour;
  const sensor_msgs::ImageConstPtr newest = colours_.getElemBeforeTime(ros::TIME_MAX);
  const double now_s = ros::WallTime::now().toSec();
  double wait_s = 0;
  if (!newest && colour_wait_.waiting(now_s)) {
    wait_s = colour_wait_.remaining(now_s);  // none yet: the subscription may still be connecting
  } else if (newest && newest->header.stamp < stamp) {
    wait_s = kLateColourS;  // this stamp's may still come
  }
  if (wait_s > 0) colour_arrived_.wait_for(lock, std::chrono::duration<double>(wait_s), [&] { return same_stamp() != nullptr; });
  return same_stamp();
}

cv::Mat LandmarkNodelet::colourImage(const sensor_msgs::Image& edges_msg, const cv::Size& size,
                                     sensor_msgs::ImageConstPtr* colour_msg) {
  const sensor_msgs::ImageConstPtr colour = waitForColour(edges_msg.header.stamp);
  *colour_msg = colour;
  if (!colour) return cv::Mat();
  PixelFormat format;
  cv::Mat view;
  std::string error;
  if (!viewImage(*colour, &format, &view, &error) || view.size() != size) return cv::Mat();
  if (format == PixelFormat::BGR8) return view;
  bgr_ = frameToBgr(view, format);  // colours learned as the tracker reads them (4:2:2: the camera's YUV)
  return bgr_;
}

bool LandmarkNodelet::camera(const cv::Size& size, PinholeCamera* camera) {
  sensor_msgs::CameraInfoConstPtr info;
  {
    // At start-up camera_info may connect after the first images: the first frame waits for
    // it (up to camera_info_wait_) rather than give a horizon without pitch.
    std::unique_lock<std::mutex> lock(info_mutex_);
    const double now_s = ros::WallTime::now().toSec();
    if (!camera_info_ && camera_info_wait_.waiting(now_s)) {
      info_arrived_.wait_for(lock, std::chrono::duration<double>(camera_info_wait_.remaining(now_s)),
                             [this] { return camera_info_ != nullptr; });
    }
    info = camera_info_;
  }
  const bool usable = info && cameraFromInfo(*info, camera) && camera->width == size.width && camera->height == size.height;
  if (!usable && !warned_no_camera_info_ && !camera_info_wait_.waiting(ros::WallTime::now().toSec())) {
    warned_no_camera_info_ = true;
    NODELET_WARN("no usable camera_info for %dx%d images on %s: horizon pitch will be NaN and markers are off",
                 size.width, size.height, sub_info_.getTopic().c_str());
  }
  return usable;
}

void LandmarkNodelet::learnColours(const std_msgs::Header& header, const cv::Mat& bgr, const LandmarkResult& result,
                                   const FieldColor& field, const Settings& s) {
  ColorLearningLoop::Step step;
  // The floor's colour goes out with the learned ranges (learning_field_class); a frame without
  // a floor in view keeps the last one published.
  if (!s.loop.field_class) learning_loop_->setFieldColour(nullptr);
  if (s.loop.field_class && field.found) learning_loop_->setFieldColour(&field.range);
  if (!s.loop.enabled) {
    step = learning_loop_->stop(s.learning);
  } else if (!bgr.empty()) {
    step = learning_loop_->learn(bgr, result, detector_.edgeObjects(), header.stamp.toSec(),
                                 ros::WallTime::now().toSec(), s.learning, s.loop.publish_period_s);
  }
  if (step.resumed > 0) NODELET_INFO("resuming from %d learned colour ranges the tracker uses", step.resumed);
  if (step.publish) publishRanges(header, step.classes);
}

void LandmarkNodelet::reportBudget(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const int over_budget = frames_over_budget_.exchange(0);
  status.add("frames whose line budget ran out (since last report)", over_budget);
  status.add("frames whose line budget ran out (total)", frames_over_budget_total_.load());
  if (over_budget == 0) return;
  status.add("edge objects skipped (last such frame)", objects_skipped_.load());
  status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN,
                      "cluttered frames: the line budget max_refinements_per_frame ran out and the smallest edge objects "
                      "were skipped (raise it, or raise min_line_length_px or the edge thresholds)");
}

void LandmarkNodelet::noteMissingColour(const std_msgs::Header& header, const cv::Size& size) {
  // The colour image of this stamp has not arrived (or was dropped): counted. Only images of
  // another camera (another size or frame) are the user's to fix.
  const sensor_msgs::ImageConstPtr newest = colours_.getElemBeforeTime(ros::TIME_MAX);
  if (!newest) return;
  ++frames_without_colour_;
  if (newest->width != static_cast<uint32_t>(size.width) || newest->height != static_cast<uint32_t>(size.height) ||
      newest->header.frame_id != header.frame_id) {
    NODELET_WARN_THROTTLE(10.0, "image_raw (%ux%u, frame '%s') and edges (%dx%d, frame '%s') come from different "
                          "cameras: no region evidence for the horizon and no colours measured",
                          newest->width, newest->height, newest->header.frame_id.c_str(), size.width, size.height,
                          header.frame_id.c_str());
  }
}

void LandmarkNodelet::publishRanges(const std_msgs::Header& header, const std::vector<ColorClass>& classes) {
  pub_ranges_.publish(colorRangesMsg(header, classes));
  ranges_published_s_ = ros::WallTime::now().toSec();
  learned_classes_ = static_cast<int>(
      std::count_if(classes.begin(), classes.end(), [](const ColorClass& c) { return c.source == "learned"; }));
}

FieldResult LandmarkNodelet::publishField(const std_msgs::Header& header, const cv::Mat& bgr, const Settings& s) {
  // Where the floor ends, from the colour image (none without one: the edges carry no colour);
  // only while someone reads it (the tracker subscribes, the overlay draws it, or the floor's
  // colour goes out on color_ranges).
  FieldResult field;
  const bool feeds_ranges = s.loop.enabled && s.loop.field_class && pub_ranges_.getNumSubscribers() > 0;
  const bool wanted = feeds_ranges || pub_field_.getNumSubscribers() > 0 || pub_debug_.getNumSubscribers() > 0;
  field_detector_.setOptions(s.field);
  if (wanted && !bgr.empty()) field_detector_.detect(bgr, &field);
  field_found_ = field.boundary.found;
  field_confidence_ = field.boundary.confidence;
  field_ms_ = field.ms;
  pub_field_.publish(fieldBoundaryToMsg(header, field.boundary));
  return field;
}

void LandmarkNodelet::publishDebug(const std_msgs::Header& header, const cv::Mat& bgr, const cv::Mat& edges,
                                   const LandmarkResult& result, const Horizon& horizon,
                                   const FieldBoundaryEstimate& field, bool learning) {
  cv::Mat canvas;
  if (!bgr.empty()) {
    canvas = bgr.clone();
  } else {
    cv::cvtColor(edges, canvas, cv::COLOR_GRAY2BGR);
  }
  drawLandmarks(&canvas, result.lines, result.horizon, horizon.roll, horizon.pitch);
  drawFieldBoundary(&canvas, field);
  if (learning) {
    drawLearning(&canvas, learning_loop_->learner().lastMeasurements());
    drawColorSwatches(&canvas, ColorTable(learning_loop_->learner().classes()));
  }
  pub_debug_.publish(debugImageMsg(header, canvas));
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::LandmarkNodelet, nodelet::Nodelet)
