// rle_vision/ImageInput: frames as robots record them, in front of the pipeline. JPEG or PNG
// frames on image_raw/compressed (sensor_msgs/CompressedImage) are decoded once and published
// on `image`, which every nodelet of the manager then shares without a copy; with ~debayer,
// Bayer frames on image_raw are demosaiced too (other frames pass through, zero-copy). OpenCV
// does both: no image_transport plugin or image_proc nodelet is needed (Debian packages neither).
//
// ~input_mode "auto" looks at the master once a second until the camera shows up, then says
// what it chose: raw frames win (a live driver offers both, and decoding would only cost time);
// without ~debayer it then stays idle and the pipeline reads image_raw itself.
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/master.h>
#include <ros/ros.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include "error_throttle.h"
#include "node_settings.h"
#include "image_conversions.h"
#include "processing_stats.h"
#include "rle_vision/io/image_input.h"

namespace rle_vision {

class ImageInputNodelet : public nodelet::Nodelet {
 private:
  void onInit() override;
  void decide();
  void connectCb();
  void compressedCb(const sensor_msgs::CompressedImageConstPtr& msg);
  void rawCb(const sensor_msgs::ImageConstPtr& msg);
  void publish(const std_msgs::Header& header, const EncodedImage& image);
  void dropFrame(const std::string& error);

  std::string input_mode_;  // settings: from the table at start
  bool debayer_{};
  std::atomic<InputChoice> choice_{InputChoice::kUndecided};
  std::string input_topic_;  // for error messages, set once decided
  ros::WallTime started_;
  bool said_waiting_ = false;
  ros::WallTimer decide_timer_;
  std::mutex connect_mutex_;
  ros::Publisher pub_image_;
  ros::Subscriber sub_input_;
  std::shared_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
  ProcessingStats stats_;
  ErrorThrottle input_errors_;
};

void ImageInputNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  std::vector<std::string> problems;
  // The RLE_IMAGE_INPUT_SETTING lines of its table: input_mode_, debayer_.
#define RLE_IMAGE_INPUT_SETTING(key, type, default_value, min, max, description) \
  key##_ = default_value;                                                       \
  readSetting(pnh, #key, &key##_, min, max, &problems);
#include "rle_vision/params/image_input_params.def"
  for (const std::string& problem : problems) NODELET_WARN("%s", problem.c_str());
  const std::string mode_error = inputModeError(input_mode_);
  if (!mode_error.empty()) {
    NODELET_ERROR("%s: using auto", mode_error.c_str());
    input_mode_ = "auto";
  }
  diagnostics_ = std::make_shared<diagnostic_updater::Updater>(nh, pnh, getName());
  diagnostics_->setHardwareID("none");
  diagnostics_->add("image input", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    stats_.report(s, 10.0);
    const InputChoice choice = choice_;
    const std::string what = describeInputChoice(choice, getNodeHandle().resolveName("image_raw"), debayer_);
    s.add("input", what);
    if (choice == InputChoice::kWrongType) s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, what);
    if (choice == InputChoice::kRaw && !debayer_) s.summary(diagnostic_msgs::DiagnosticStatus::OK, "idle: " + what);
  });
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->update(); });
  started_ = ros::WallTime::now();
  decide();
  if (choice_ == InputChoice::kUndecided || choice_ == InputChoice::kWrongType) {
    decide_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { decide(); });
  }
}

void ImageInputNodelet::decide() {
  if (choice_ == InputChoice::kRaw || choice_ == InputChoice::kCompressed) return;
  const std::string raw_topic = getNodeHandle().resolveName("image_raw");
  std::string raw_type;
  bool compressed_published = false;
  ros::master::V_TopicInfo topics;
  if (ros::master::getTopics(topics)) {
    for (const ros::master::TopicInfo& topic : topics) {
      if (topic.name == raw_topic) raw_type = topic.datatype;
      compressed_published = compressed_published || topic.name == raw_topic + "/compressed";
    }
  }
  choice_ = chooseInput(input_mode_, raw_type, compressed_published);
  const std::string what = describeInputChoice(choice_, raw_topic, debayer_);
  if (choice_ == InputChoice::kWrongType) {
    // Wall-time throttle: a bag's player sets use_sim_time, and its clock may not run yet.
    if (input_errors_.shouldLog(what)) NODELET_ERROR("%s", what.c_str());
    return;
  }
  if (choice_ == InputChoice::kUndecided) {
    if (!said_waiting_ && (ros::WallTime::now() - started_).toSec() > 5.0) {
      NODELET_INFO("%s", what.c_str());
      said_waiting_ = true;
    }
    return;
  }
  decide_timer_.stop();
  NODELET_INFO("%s", what.c_str());
  input_topic_ = choice_ == InputChoice::kCompressed ? raw_topic + "/compressed" : raw_topic;
  if (choice_ == InputChoice::kRaw && !debayer_) return;  // the pipeline reads image_raw itself
  std::lock_guard<std::mutex> lock(connect_mutex_);
  const ros::SubscriberStatusCallback connect_cb = [this](const ros::SingleSubscriberPublisher&) { connectCb(); };
  pub_image_ = getNodeHandle().advertise<sensor_msgs::Image>("image", 1, connect_cb, connect_cb);
}

// Lazy: the camera's frames are only read (and a driver only compresses them) while someone
// reads `image`.
void ImageInputNodelet::connectCb() {
  std::lock_guard<std::mutex> lock(connect_mutex_);
  if (pub_image_.getNumSubscribers() == 0) {
    sub_input_.shutdown();
  } else if (!sub_input_) {
    ros::NodeHandle& nh = getNodeHandle();
    if (choice_ == InputChoice::kCompressed) {
      sub_input_ = nh.subscribe("image_raw/compressed", 1, &ImageInputNodelet::compressedCb, this);
    } else {
      sub_input_ = nh.subscribe("image_raw", 1, &ImageInputNodelet::rawCb, this);
    }
  }
}

void ImageInputNodelet::compressedCb(const sensor_msgs::CompressedImageConstPtr& msg) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = threadCpuMs();
  EncodedImage decoded;
  std::string error;
  if (!decodeCompressedImage(msg->format, msg->data.data(), msg->data.size(), &decoded, &error)) return dropFrame(error);
  // Decoded Bayer mosaics are always demosaiced: nothing downstream reads them.
  if (isBayerEncoding(decoded.encoding)) {
    cv::Mat bgr;
    if (!demosaicBayer(decoded.image, decoded.encoding, &bgr, &error)) return dropFrame(error);
    decoded = {bgr, "bgr8"};
  }
  publish(msg->header, decoded);
  stats_.addFrame(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                  threadCpuMs() - cpu_start_ms);
}

void ImageInputNodelet::rawCb(const sensor_msgs::ImageConstPtr& msg) {
  if (!isBayerEncoding(msg->encoding)) {
    pub_image_.publish(msg);  // not a mosaic: handed on as it is (shared, no copy)
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = threadCpuMs();
  std::string error;
  cv::Mat mosaic;
  if (!viewImageBytes(*msg, CV_8UC1, &mosaic, &error)) return dropFrame(error);
  cv::Mat bgr;
  if (!demosaicBayer(mosaic, msg->encoding, &bgr, &error)) return dropFrame(error);
  publish(msg->header, {bgr, "bgr8"});
  stats_.addFrame(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                  threadCpuMs() - cpu_start_ms);
}

void ImageInputNodelet::publish(const std_msgs::Header& header, const EncodedImage& image) {
  auto out = boost::make_shared<sensor_msgs::Image>();
  out->header = header;
  out->encoding = image.encoding;
  out->width = static_cast<uint32_t>(image.image.cols);
  out->height = static_cast<uint32_t>(image.image.rows);
  out->step = static_cast<uint32_t>(image.image.cols * image.image.elemSize());
  out->data.resize(static_cast<size_t>(out->step) * out->height);
  cv::Mat view(image.image.rows, image.image.cols, image.image.type(), out->data.data(), out->step);
  image.image.copyTo(view);
  pub_image_.publish(out);
}

void ImageInputNodelet::dropFrame(const std::string& error) {
  stats_.addDrop();
  if (input_errors_.shouldLog(error)) {
    NODELET_ERROR("dropping frame on %s: %s", input_topic_.c_str(), error.c_str());
  }
}

}  // namespace rle_vision

PLUGINLIB_EXPORT_CLASS(rle_vision::ImageInputNodelet, nodelet::Nodelet)
