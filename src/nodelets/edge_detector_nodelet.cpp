// rle_vision/EdgeDetector: the paper's 5x5 RGB Sobel: image_raw -> edges (mono8, the largest
// channel gradient magnitude), stamped with the input header. Works only while `edges` has
// subscribers, on its own low-priority thread with a one-slot mailbox like the Landmark node:
// edges feed only the low-priority landmark path, so they must not take a core from the
// tracker when both get the same image.
#include <chrono>
#include <memory>
#include <mutex>

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>

#include "image_conversions.h"
#include "error_throttle.h"
#include "node_settings.h"
#include "low_priority_worker.h"
#include "processing_stats.h"
#include "startup_params.h"
#include "rle_vision/EdgeDetectorConfig.h"
#include "rle_vision/edges/sobel5.h"

namespace rle_vision {

class EdgeDetectorNodelet : public nodelet::Nodelet {
 public:
  ~EdgeDetectorNodelet() override { worker_.stop(); }

 private:
  void onInit() override;
  void connectCb();
  void imageCb(const sensor_msgs::ImageConstPtr& msg);
  void process(const sensor_msgs::ImageConstPtr& msg);

  std::shared_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber sub_image_;
  image_transport::Publisher pub_edges_;
  std::mutex connect_mutex_;
  std::mutex config_mutex_;
  double edge_gain_ = 2.0;
  std::shared_ptr<dynamic_reconfigure::Server<EdgeDetectorConfig>> reconfigure_server_;
  std::shared_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  ProcessingStats stats_;
  ErrorThrottle input_errors_;  // bad input, per kind of problem
  // Used only by the worker thread.
  Sobel5 sobel_;
  cv::Mat bgr_;
  LowPriorityWorker worker_;
};

void EdgeDetectorNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_shared<image_transport::ImageTransport>(nh);
  std::vector<std::string> problems;
  // The RLE_EDGE_SETTING lines of its table (low_priority), each a local variable.
#define RLE_EDGE_SETTING(key, type, default_value, min, max, description) \
  type key = default_value;                                              \
  readSetting(pnh, #key, &key, min, max, &problems);
#include "rle_vision/params/landmark_params.def"
  for (const std::string& problem : problems) NODELET_WARN("%s", problem.c_str());
  for (const std::string& problem : startupParamProblems<EdgeDetectorConfig>(pnh)) NODELET_WARN("%s", problem.c_str());
  reconfigure_server_ = std::make_shared<dynamic_reconfigure::Server<EdgeDetectorConfig>>(pnh);
  reconfigure_server_->setCallback([this](EdgeDetectorConfig& config, uint32_t) {
    if (!std::isfinite(config.edge_gain) || config.edge_gain <= 0) {
      NODELET_WARN("edge_gain must be a finite number > 0: keeping %.3f", edge_gain_);
      config.edge_gain = edge_gain_;
    }
    std::lock_guard<std::mutex> lock(config_mutex_);
    edge_gain_ = config.edge_gain;
  });
  diagnostics_ = std::make_shared<diagnostic_updater::Updater>(nh, pnh, getName());
  diagnostics_->setHardwareID("none");
  diagnostics_->add("edge detector", [this](diagnostic_updater::DiagnosticStatusWrapper& s) { stats_.report(s, 5.0); });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });
  worker_.start(
      low_priority, [this](const sensor_msgs::ImageConstPtr& msg) { process(msg); },
      [this, low_priority](bool niced, bool idled) {
        if (low_priority) {
          NODELET_INFO("edge worker runs at low priority (nice 19: %s, SCHED_IDLE: %s)", niced ? "yes" : "no",
                       idled ? "yes" : "no");
        }
      },
      [this](const char* what) { NODELET_ERROR_THROTTLE(5.0, "edge detection failed: %s", what); });

  std::lock_guard<std::mutex> lock(connect_mutex_);
  const image_transport::SubscriberStatusCallback connect_cb =
      [this](const image_transport::SingleSubscriberPublisher&) { connectCb(); };
  pub_edges_ = it_->advertise("edges", 1, connect_cb, connect_cb);
}

void EdgeDetectorNodelet::connectCb() {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  if (pub_edges_.getNumSubscribers() == 0) {
    sub_image_.shutdown();
  } else if (!sub_image_) {
    sub_image_ = it_->subscribe("image_raw", 1, &EdgeDetectorNodelet::imageCb, this);
  }
}

void EdgeDetectorNodelet::imageCb(const sensor_msgs::ImageConstPtr& msg) {
  if (worker_.put(msg)) stats_.addDrop();  // the worker did not get to the previous frame
}

void EdgeDetectorNodelet::process(const sensor_msgs::ImageConstPtr& msg) {
  const FrameClock clock;
  CameraFrame frame;
  const auto log_error = [this](const std::string& text) { NODELET_ERROR("%s", text.c_str()); };
  if (!viewCameraImage(*msg, getNodeHandle().resolveName("image_raw"), &input_errors_, &frame, log_error)) return;
  // The Sobel works on any channel order (it keeps the largest channel magnitude); 4:2:2
  // is converted to BGR first.
  const PixelFormat format = frame.format;
  const cv::Mat& image = frame.image;
  const cv::Mat* input = &image;
  if (format == PixelFormat::UYVY || format == PixelFormat::YUYV) {
    cv::cvtColor(image, bgr_, format == PixelFormat::UYVY ? cv::COLOR_YUV2BGR_UYVY : cv::COLOR_YUV2BGR_YUY2);
    input = &bgr_;
  }
  double gain;
  {
    std::lock_guard<std::mutex> lock(config_mutex_);
    gain = edge_gain_;
  }
  // The Sobel writes straight into the outgoing message's buffer (no copy).
  auto out = boost::make_shared<sensor_msgs::Image>();
  out->header = msg->header;
  out->encoding = "mono8";
  out->width = msg->width;
  out->height = msg->height;
  out->step = msg->width;
  out->data.resize(static_cast<size_t>(out->step) * out->height);
  cv::Mat edges(static_cast<int>(out->height), static_cast<int>(out->width), CV_8UC1, out->data.data(), out->step);
  sobel_.edges(*input, gain, &edges);
  pub_edges_.publish(out);
  stats_.addFrame(clock.elapsedMs(), clock.cpuMs());
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::EdgeDetectorNodelet, nodelet::Nodelet)
