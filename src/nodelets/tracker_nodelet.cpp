// rle_vision/Tracker: the real-time RLE colour blob tracker. A thin wrapper around the core
// ColorTracker (Segmenter + BlobTracker): converts messages, holds the parameters, publishes
// blobs (and, for cmvision users, the same blobs in cmvision's message shape).
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cstring>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <mutex>
#include <thread>

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "blob_conversions.h"
#include "color_range_conversions.h"
#include "image_conversions.h"
#include "error_throttle.h"
#include "field_conversions.h"
#include "node_settings.h"
#include "tracker_conversions.h"
#include "inline_callback_queue.h"
#include "processing_stats.h"
#include "startup_params.h"
#include "rle_vision/BlobArray.h"
#include "rle_vision/CmvisionBlobs.h"
#include "rle_vision/ColorRangeArray.h"
#include "rle_vision/TrackerConfig.h"
#include "rle_vision/field/on_field.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/tracking/color_tracker.h"
#include "rle_vision/common/latency_histogram.h"
#include "rle_vision/pipeline/overlay.h"
#include "rle_vision/segment/region_load.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/color/shared_color_table.h"
#include "rle_vision/verify/candidate_screen.h"

namespace rle_vision {

class TrackerNodelet : public nodelet::Nodelet {
 public:
  ~TrackerNodelet() override;

 private:
  void onInit() override;
  void loadColours(const std::string& setting, int max_candidates_per_frame);
  void connectCb();
  void imageCb(const sensor_msgs::ImageConstPtr& msg);
  void colorRangesCb(const ColorRangeArrayConstPtr& msg);
  void fieldBoundaryCb(const FieldBoundaryConstPtr& msg);
  FieldBoundaryEstimate fieldBoundaryAt(const ros::Time& stamp);
  void setUpOnField(ros::NodeHandle& nh, const std::string& classes, double margin_px, double max_age_s);
  void screenCandidates(const CameraFrame& frame, const ColorTable& table);
  void reportVerifier(diagnostic_updater::DiagnosticStatusWrapper& status);
  void reconfigureCb(TrackerConfig& config, uint32_t level);
  void publishActiveRanges(const ColorTable& table, const ros::Time& stamp);
  void reportDiagnostics(diagnostic_updater::DiagnosticStatusWrapper& status);
  void reportRegionLoad(diagnostic_updater::DiagnosticStatusWrapper& status);

  // With SCHED_FIFO, images arrive on a queue served by a thread of the tracker's own, so a
  // frame never waits behind another nodelet's callback on the manager's shared worker threads.
  // At normal priority they are processed in the thread that delivers them (inline_queue_), the
  // frame thread serving only what cannot run there. Declared before the subscriber so that
  // they outlive it.
  ros::CallbackQueue frame_queue_;
  InlineCallbackQueue inline_queue_{&frame_queue_};
  std::atomic<bool> frame_thread_running_{true};
  std::thread frame_thread_;
  std::shared_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber sub_image_;
  ros::Subscriber sub_ranges_, sub_field_;
  ros::Publisher pub_blobs_, pub_cmvision_blobs_;
  ros::Publisher pub_active_ranges_;
  image_transport::Publisher pub_debug_;
  std::mutex connect_mutex_;
  int queue_size_ = 1;
  bool publish_cmvision_blobs_ = false;

  // Parameters are copied under this mutex, then frames are processed without it.
  std::mutex config_mutex_;
  SegmenterOptions segmenter_options_;
  TrackerOptions tracker_options_;
  std::shared_ptr<dynamic_reconfigure::Server<TrackerConfig>> reconfigure_server_;

  // Swapped by colorRangesCb while imageCb segments with its own snapshot.
  SharedColorTable table_;
  std::atomic<bool> warned_mono_{false};
  // When the current table arrived and where it came from, for diagnostics.
  std::mutex table_info_mutex_;
  ros::WallTime table_since_;
  std::string table_source_ = "config";

  std::shared_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  ProcessingStats stats_;
  ErrorThrottle input_errors_;  // bad input, per kind of problem
  // Image stamp to blobs publish, since start (wall-clock time only; meaningless under sim time).
  std::mutex latency_mutex_;
  LatencyHistogram latency_;
  RegionLoadMonitor region_load_;  // frames with more regions than the tracker keeps

  // The latest field boundary (from the Landmark node) and which blobs must lie on its field side.
  std::mutex field_mutex_;
  FieldBoundaryEstimate field_;
  ros::Time field_stamp_;
  std::unique_ptr<OnFieldFilter> on_field_;
  double field_max_age_s_ = 0.5;
  std::atomic<uint64_t> dropped_off_field_{0}, dropped_off_field_total_{0};

  // Classes with a verifier (verifier_file in the colours file): their blobs are scored and
  // screened. Counts for diagnostics: since the last report, and in total.
  CandidateScreen screen_;
  std::mutex screen_counts_mutex_;
  ScreeningCounts screened_, screened_total_;
  uint64_t frames_over_cap_ = 0;
  cv::Mat verifier_bgr_;  // the frame as BGR, for formats other than bgr8

  // Used only by imageCb, which ROS calls serially.
  ColorTracker color_tracker_;
  std::vector<TrackedBlob> blobs_;
  std::vector<double> above_field_;
};

TrackerNodelet::~TrackerNodelet() {
  // Frames may be processed in other threads (inline at normal priority): unsubscribing waits
  // for one in progress, so none runs on members being destroyed.
  {
    std::lock_guard<std::mutex> lock(connect_mutex_);
    sub_image_.shutdown();
  }
  frame_thread_running_ = false;
  if (frame_thread_.joinable()) frame_thread_.join();
}

// What the Tracker reads once at start: the RLE_TRACKER_SETTING lines of its table.
struct TrackerSettings {
#define RLE_TRACKER_SETTING(key, type, default_value, min, max, description) type key = default_value;
#include "rle_vision/params/tracker_params.def"
};

void TrackerNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  TrackerSettings settings;
  std::vector<std::string> problems;
#define RLE_TRACKER_SETTING(key, type, default_value, min, max, description) \
  readSetting(pnh, #key, &settings.key, min, max, &problems);
#include "rle_vision/params/tracker_params.def"
  for (const std::string& problem : problems) NODELET_WARN("%s", problem.c_str());
  const int realtime_priority = settings.realtime_priority;
  auto realtime_promise = std::make_shared<std::promise<bool>>();
  std::future<bool> realtime = realtime_promise->get_future();
  frame_thread_ = std::thread([this, realtime_priority, realtime_promise] {
    bool fifo = false;
    if (realtime_priority > 0) {
      // SCHED_FIFO needs CAP_SYS_NICE or an rtprio limit (/etc/security/limits.conf).
      sched_param param{};
      param.sched_priority = std::min(realtime_priority, sched_get_priority_max(SCHED_FIFO));
      const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
      fifo = error == 0;
      if (!fifo) {
        // Informational: most desktop users lack the permission and the tracker still works.
        NODELET_INFO("tracker frames run at normal priority, in the thread that delivers them: SCHED_FIFO "
                     "priority %d is not allowed (%s). For the lowest latency allow it with an rtprio limit in "
                     "/etc/security/limits.conf; ~realtime_priority 0 silences this",
                     param.sched_priority, strerror(error));
      } else {
        NODELET_INFO("tracker frame thread runs at SCHED_FIFO priority %d", param.sched_priority);
      }
    }
    realtime_promise->set_value(fifo);
    while (frame_thread_running_) frame_queue_.callAvailable(ros::WallDuration(0.1));
  });
  ros::NodeHandle frame_nh(nh);
  if (realtime.get()) {
    frame_nh.setCallbackQueue(&frame_queue_);
  } else {
    frame_nh.setCallbackQueue(&inline_queue_);
    if (realtime_priority <= 0) NODELET_INFO("tracker frames run at normal priority, in the thread that delivers them");
  }
  it_ = std::make_shared<image_transport::ImageTransport>(frame_nh);
  queue_size_ = settings.queue_size;
  publish_cmvision_blobs_ = settings.publish_cmvision_blobs;

  loadColours(settings.colors_file, settings.verifier_max_candidates_per_frame);
  table_since_ = ros::WallTime::now();
  setUpOnField(nh, settings.on_field_classes, settings.on_field_margin_px, settings.field_boundary_max_age_s);

  for (const std::string& problem : startupParamProblems<TrackerConfig>(pnh)) NODELET_WARN("%s", problem.c_str());
  reconfigure_server_ = std::make_shared<dynamic_reconfigure::Server<TrackerConfig>>(pnh);
  reconfigure_server_->setCallback([this](TrackerConfig& config, uint32_t level) { reconfigureCb(config, level); });
  diagnostics_ = std::make_shared<diagnostic_updater::Updater>(nh, pnh, getName());
  diagnostics_->setHardwareID("none");
  diagnostics_->add("tracker", [this](diagnostic_updater::DiagnosticStatusWrapper& s) { reportDiagnostics(s); });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });

  // Lazy: the image is only subscribed while someone listens to an output.
  std::lock_guard<std::mutex> lock(connect_mutex_);
  const ros::SubscriberStatusCallback connect_cb = [this](const ros::SingleSubscriberPublisher&) { connectCb(); };
  const image_transport::SubscriberStatusCallback image_connect_cb =
      [this](const image_transport::SingleSubscriberPublisher&) { connectCb(); };
  pub_blobs_ = nh.advertise<BlobArray>("blobs", 10, connect_cb, connect_cb);
  pub_debug_ = image_transport::ImageTransport(pnh).advertise("debug_image", 1, image_connect_cb, image_connect_cb);
  if (publish_cmvision_blobs_) {
    pub_cmvision_blobs_ = nh.advertise<CmvisionBlobs>("cmvision_blobs", 10, connect_cb, connect_cb);
  }
  pub_active_ranges_ = pnh.advertise<ColorRangeArray>("active_color_ranges", 1, /*latch=*/true);
  sub_ranges_ = nh.subscribe("color_ranges", 1, &TrackerNodelet::colorRangesCb, this);
  publishActiveRanges(*table_.load(), ros::Time::now());
}

// The colour classes of ~colors_file and the verifiers they name; a file that cannot be used
// stops the tracker with the fix.
void TrackerNodelet::loadColours(const std::string& setting, int max_candidates_per_frame) {
  const std::string colors_file =
      setting.empty() ? ros::package::getPath("rle_vision") + "/config/colors.yaml" : setting;
  std::vector<ColorClass> classes;
  try {
    classes = loadColorClasses(colors_file);
  } catch (const std::exception& e) {
    // Fail loudly at start: without classes the tracker cannot do anything useful.
    NODELET_FATAL("cannot load colour classes: %s. Set ~colors_file to a colors.yaml or CMVision colors.txt.", e.what());
    throw;
  }
  NODELET_INFO("loaded %zu colour classes from %s", classes.size(), colors_file.c_str());
  try {
    screen_ = CandidateScreen(loadClassVerifiers(classes), static_cast<uint32_t>(max_candidates_per_frame));
  } catch (const std::exception& e) {
    NODELET_FATAL("%s. Fix the class's verifier_file in %s (rle_vision_train writes the file), or remove it.", e.what(),
                  colors_file.c_str());
    throw;
  }
  table_.store(std::make_shared<const ColorTable>(withFloorGuard(std::move(classes), screen_.verifiers())));
  for (const ClassVerifier& v : screen_.verifiers()) {
    NODELET_INFO("class '%s' is screened by a verifier: blobs scoring under %.2f are not published", v.class_name.c_str(),
                 v.min_score);
  }
}

void TrackerNodelet::connectCb() {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  if (pub_blobs_.getNumSubscribers() == 0 && pub_debug_.getNumSubscribers() == 0 &&
      pub_cmvision_blobs_.getNumSubscribers() == 0) {
    sub_image_.shutdown();
  } else if (!sub_image_) {
    sub_image_ = it_->subscribe("image_raw", static_cast<uint32_t>(queue_size_), &TrackerNodelet::imageCb, this);
  }
}

void TrackerNodelet::reconfigureCb(TrackerConfig& config, uint32_t /*level*/) {
  if (config.connectivity != 4 && config.connectivity != 8) {
    NODELET_WARN("connectivity must be 4 or 8, got %d: using 8", config.connectivity);
    config.connectivity = 8;
  }
  std::lock_guard<std::mutex> lock(config_mutex_);
  const std::string not_finite = nonFiniteTrackerParam(config);
  if (!not_finite.empty()) {
    NODELET_WARN("%s is not a finite number: keeping the previous tracker parameters", not_finite.c_str());
    configFromOptions(segmenter_options_, tracker_options_, &config);  // rqt_reconfigure shows what is in effect
    return;
  }
  optionsFromConfig(config, &segmenter_options_, &tracker_options_);
}

void TrackerNodelet::colorRangesCb(const ColorRangeArrayConstPtr& msg) {
  std::vector<ColorClass> classes;
  std::string error;
  if (!colorClassesFromMsg(*msg, &classes, &error)) {
    if (input_errors_.shouldLog(error)) {
      NODELET_ERROR("ignoring color_ranges: %s; keeping the current %d classes", error.c_str(), table_.load()->size());
    }
    return;
  }
  // Built here, off the frame path; imageCb picks it up with its next snapshot. The floor's
  // guard follows the field class the set brings (screen_ is set once, before subscribing).
  auto table = std::make_shared<const ColorTable>(withFloorGuard(std::move(classes), screen_.verifiers()));
  table_.store(table);
  warned_mono_ = false;
  {
    std::lock_guard<std::mutex> lock(table_info_mutex_);
    table_since_ = ros::WallTime::now();
    table_source_ = std::any_of(table->classes().begin(), table->classes().end(),
                                [](const ColorClass& c) { return c.source == "learned"; })
                        ? "color_ranges (learned)"
                        : "color_ranges";
  }
  NODELET_DEBUG("swapped in %d colour classes from color_ranges", table->size());
  publishActiveRanges(*table, msg->header.stamp);
}

void TrackerNodelet::setUpOnField(ros::NodeHandle& nh, const std::string& classes, double margin_px, double max_age_s) {
  on_field_ = std::make_unique<OnFieldFilter>(classes, margin_px);
  field_max_age_s_ = max_age_s;
  for (const std::string& name : on_field_->unknownClasses(*table_.load())) {
    NODELET_WARN("~on_field_classes names '%s', which is not one of the colour classes: check the spelling", name.c_str());
  }
  // Every blob gets its height above the field (Blob.above_field_px) when a boundary is known.
  sub_field_ = nh.subscribe("field_boundary", 1, &TrackerNodelet::fieldBoundaryCb, this);
}

void TrackerNodelet::fieldBoundaryCb(const FieldBoundaryConstPtr& msg) {
  const FieldBoundaryEstimate boundary = fieldBoundaryFromMsg(*msg);
  std::lock_guard<std::mutex> lock(field_mutex_);
  field_ = boundary;
  field_stamp_ = msg->header.stamp;
}

FieldBoundaryEstimate TrackerNodelet::fieldBoundaryAt(const ros::Time& stamp) {
  // The landmark path runs behind the tracker: the newest boundary is a frame or a few old.
  std::lock_guard<std::mutex> lock(field_mutex_);
  if (field_stamp_.isZero() || std::fabs((stamp - field_stamp_).toSec()) > field_max_age_s_) return {};
  return field_;
}

void TrackerNodelet::publishActiveRanges(const ColorTable& table, const ros::Time& stamp) {
  ColorRangeArray msg;
  msg.header.stamp = stamp;
  for (const ColorClass& c : table.classes()) msg.ranges.push_back(colorRangeToMsg(c));
  pub_active_ranges_.publish(msg);
}

void TrackerNodelet::imageCb(const sensor_msgs::ImageConstPtr& msg) {
  const FrameClock clock;
  CameraFrame frame;
  if (!viewCameraImage(*msg, getNodeHandle().resolveName("image_raw"), &input_errors_, &frame,
                       [this](const std::string& text) { NODELET_ERROR("%s", text.c_str()); })) {
    return;
  }
  const PixelFormat format = frame.format;
  const cv::Mat& image = frame.image;
  const std::shared_ptr<const ColorTable> table = table_.load();
  if (format == PixelFormat::MONO8 && table->chromaClasses() != 0 && !warned_mono_.exchange(true)) {
    NODELET_WARN("mono8 images carry no colour: the %d classes that constrain chroma are skipped "
                 "(only classes with full U/V, H/S or equal R/G/B ranges apply)",
                 __builtin_popcount(table->chromaClasses()));
  }
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    color_tracker_.setOptions(segmenter_options_, tracker_options_);
  }
  color_tracker_.process(image, format, *table, msg->header.stamp.toSec(), &blobs_);
  if (color_tracker_.tracker().lastUpdateRestarted()) {
    NODELET_WARN("image time went backwards (a looped bag?): track ids start over");
  }
  // Overloaded classes are logged once, then counted for diagnostics.
  const RegionLimits& limits = color_tracker_.tracker().options().limits;
  const std::string overload = firstOverloadLog(
      region_load_.addFrame(color_tracker_.regionCounts(), static_cast<uint32_t>(blobs_.size()),
                            limits.max_regions_per_class),
      color_tracker_.regionCounts(), *table, limits);
  if (!overload.empty()) NODELET_WARN("%s", overload.c_str());

  const int off_field = on_field_->apply(fieldBoundaryAt(msg->header.stamp), *table, &blobs_, &above_field_);
  dropped_off_field_ += off_field;
  dropped_off_field_total_ += off_field;
  screenCandidates(frame, *table);

  auto out = boost::make_shared<BlobArray>();
  out->header = msg->header;
  out->image_width = msg->width;
  out->image_height = msg->height;
  out->blobs.reserve(blobs_.size());
  for (size_t i = 0; i < blobs_.size(); ++i) {
    out->blobs.push_back(blobToMsg(blobs_[i], table->classes()[blobs_[i].region.label - 1].name));
    out->blobs.back().above_field_px = static_cast<float>(above_field_[i]);
  }
  out->processing_time_ms = static_cast<float>(clock.elapsedMs());
  const double cpu_ms = clock.cpuMs();  // the same span as processing_time_ms
  pub_blobs_.publish(out);
  const double latency_ms = (ros::Time::now() - msg->header.stamp).toSec() * 1e3;
  if (ros::Time::useSystemTime() && latency_ms > -1e3 && latency_ms < 1e4) {  // a live camera's stamp
    std::lock_guard<std::mutex> lock(latency_mutex_);
    latency_.add(latency_ms);
  }
  if (pub_cmvision_blobs_.getNumSubscribers() > 0) {
    pub_cmvision_blobs_.publish(cmvisionBlobsMsg(*out, *table));
  }
  stats_.addFrame(out->processing_time_ms, cpu_ms);

  if (pub_debug_.getNumSubscribers() > 0) {
    cv::Mat canvas = toDisplayBgr(image, format);
    drawBlobs(&canvas, blobs_, *table);
    drawColorSwatches(&canvas, *table);
    pub_debug_.publish(debugImageMsg(msg->header, canvas));
  }
}

void TrackerNodelet::screenCandidates(const CameraFrame& frame, const ColorTable& table) {
  if (!screen_.hasCandidates(table, blobs_)) return;
  // The verifier judges BGR pixels, as it was trained: other formats are converted for it.
  const cv::Mat* bgr = &frame.image;
  if (frame.format != PixelFormat::BGR8) {
    toDisplayBgr(frame.image, frame.format, &verifier_bgr_);  // into the buffer of the frames before
    bgr = &verifier_bgr_;
  }
  const ScreeningCounts counts = screen_.apply(*bgr, table, &blobs_, &above_field_);
  std::lock_guard<std::mutex> lock(screen_counts_mutex_);
  screened_.add(counts);
  screened_total_.add(counts);
  frames_over_cap_ += counts.over_cap > 0;
}

void TrackerNodelet::reportVerifier(diagnostic_updater::DiagnosticStatusWrapper& status) {
  if (screen_.empty()) return;
  std::lock_guard<std::mutex> lock(screen_counts_mutex_);
  status.add("verifier candidates scored (since last report)", screened_.scored);
  status.add("verifier candidates rejected under min_score (since last report)", screened_.rejected);
  status.add("verifier candidates dropped unjudged over the cap (since last report)", screened_.over_cap);
  status.add("verifier candidates rejected under min_score (total)", screened_total_.rejected);
  status.add("verifier candidates dropped unjudged over the cap (total)", screened_total_.over_cap);
  if (frames_over_cap_ > 0) {
    status.mergeSummaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                         "%lu frames had more verifier candidates than ~verifier_max_candidates_per_frame (%u): "
                         "raise it, or narrow the verified class's colour range",
                         static_cast<unsigned long>(frames_over_cap_), screen_.maxCandidatesPerFrame());
  }
  screened_ = ScreeningCounts();
  frames_over_cap_ = 0;
}

void TrackerNodelet::reportDiagnostics(diagnostic_updater::DiagnosticStatusWrapper& status) {
  stats_.report(status, 0.5);
  {
    std::lock_guard<std::mutex> lock(latency_mutex_);
    status.add("latency frames (since start)", latency_.count());
    status.add("latency image stamp to blobs p50 (ms)", latency_.percentileMs(50));
    status.add("latency image stamp to blobs p99 (ms)", latency_.percentileMs(99));
    status.add("latency image stamp to blobs max (ms)", latency_.maxMs());
    // Counts, not percentiles: two readings give a window's share over each bound (make
    // bench-latency reads them so that start-up does not count).
    for (const char* ms : {"0.5", "1", "1.5", "2", "3", "5"}) {
      status.add(std::string("latency frames over ") + ms + " ms (since start)", latency_.countAbove(std::stod(ms)));
    }
  }
  reportRegionLoad(status);
  reportVerifier(status);
  status.add("blobs dropped beyond the field boundary (since last report)", dropped_off_field_.exchange(0));
  status.add("blobs dropped beyond the field boundary (total)", dropped_off_field_total_.load());
  std::lock_guard<std::mutex> lock(table_info_mutex_);
  status.add("colour classes", table_.load()->size());
  status.add("colour ranges from", table_source_);
  status.add("colour ranges age (s)", (ros::WallTime::now() - table_since_).toSec());
}

void TrackerNodelet::reportRegionLoad(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const RegionLoadReport report = region_load_.takeReport();
  const std::shared_ptr<const ColorTable> table = table_.load();
  RegionLimits limits;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    limits = tracker_options_.limits;
  }
  status.add("regions (last frame)", report.regions);
  status.add("regions tracked (last frame)", report.tracked);
  for (const ClassLoad& load : report.overloaded) {
    if (load.label - 1 < table->size() && !yieldsBlobs(table->classes()[load.label - 1])) continue;
    const std::string name =
        load.label - 1 < table->size() ? table->classes()[load.label - 1].name : "#" + std::to_string(load.label - 1);
    status.add("frames with too many regions for class " + name + " (since last report)", load.frames_overloaded);
    status.add("frames with too many regions for class " + name + " (total)", load.frames_overloaded_total);
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, overloadMessage(name, load.most_regions, limits));
  }
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::TrackerNodelet, nodelet::Nodelet)
