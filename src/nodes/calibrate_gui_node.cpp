// calibrate_gui: the calibration window (rle_vision_calibrate --gui) on a live camera topic.
// Drag a box around the object on the live image (the frame freezes under the box); the class
// is re-measured from every boxed frame and its mask drawn on the live image. s saves it into
// ~output (colors.yaml) and ~cmvision (colors.txt); t sends it to the running tracker: the
// tracker's own class set (heard on tracker/active_color_ranges) with this class in place, on
// color_ranges.
//
//   rosrun rle_vision calibrate_gui image:=/my_cam/image_raw _name:=ball _output:=colors.yaml
#include <algorithm>
#include <mutex>
#include <string>
#include <vector>

#include <image_transport/image_transport.h>
#include <ros/ros.h>

#include "calibrate_gui/calibration_window.h"
#include "color_range_conversions.h"
#include "error_throttle.h"
#include "image_conversions.h"
#include "rle_vision/color/color_convert.h"
#include "rle_vision/io/color_config.h"

namespace rle_vision {

struct CalibrateGuiSettings {
  std::string name, output, cmvision;
  CalibrationOptions options;
};

CalibrateGuiSettings readSettings(const ros::NodeHandle& pnh) {
  CalibrateGuiSettings s;
  std::string space;
  int min_area_px = 20;
  bool background_gate = true;
  pnh.param<std::string>("name", s.name, "ball");
  pnh.param<std::string>("output", s.output, "");
  pnh.param<std::string>("cmvision", s.cmvision, "");
  pnh.param<std::string>("space", space, "YUV");
  pnh.param("min_area_px", min_area_px, 20);
  pnh.param("background_gate", background_gate, true);
  if (!parseColorSpace(space, &s.options.space)) throw std::invalid_argument("~space: unknown colour space '" + space + "' (YUV, RGB or HSV)");
  if (min_area_px < 1) throw std::invalid_argument("~min_area_px must be >= 1");
  if (!s.cmvision.empty() && s.options.space != ColorSpace::YUV) {
    throw std::invalid_argument("~cmvision: CMVision's colors.txt holds YUV classes only; use _space:=YUV or leave it out");
  }
  s.options.min_area_px = static_cast<uint32_t>(min_area_px);
  s.options.exclude_background = background_gate;
  return s;
}

class CalibrateGui {
 public:
  explicit CalibrateGui(const CalibrateGuiSettings& settings)
      : settings_(settings), session_(settings.name, settings.options), it_(nh_) {
    image_sub_ = it_.subscribe("image", 1, &CalibrateGui::imageCb, this);
    active_sub_ = nh_.subscribe("tracker/active_color_ranges", 1, &CalibrateGui::activeCb, this);
    ranges_pub_ = nh_.advertise<ColorRangeArray>("color_ranges", 1, /*latch=*/true);
  }

  void run() {
    CalibrationWindow window(&session_, /*live=*/true, "rle_vision calibrate " + image_sub_.getTopic());
    ros::AsyncSpinner spinner(1);  // callbacks beside the window, which must stay on this thread
    spinner.start();
    window.setNotice("waiting for images on " + image_sub_.getTopic());
    while (ros::ok()) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!latest_.empty()) window.setLiveFrame(latest_);
      }
      const CalibrationCommand command = window.step(30);
      if (command == CalibrationCommand::kQuit) break;
      if (command == CalibrationCommand::kSave) window.setNotice(save());
      if (command == CalibrationCommand::kSendToTracker) window.setNotice(send());
    }
  }

 private:
  void imageCb(const sensor_msgs::ImageConstPtr& msg) {
    CameraFrame frame;
    if (!viewCameraImage(*msg, image_sub_.getTopic(), &throttle_, &frame,
                         [](const std::string& e) { ROS_ERROR("%s", e.c_str()); })) {
      return;
    }
    // A copy (the message's buffer goes with it), in the YUV the tracker reads.
    cv::Mat bgr = frameToBgr(frame.image, frame.format);
    std::lock_guard<std::mutex> lock(mutex_);
    latest_ = bgr;
  }

  void activeCb(const ColorRangeArrayConstPtr& msg) {
    std::vector<ColorClass> classes;
    std::string error;
    if (!colorClassesFromMsg(*msg, &classes, &error)) {
      ROS_ERROR_THROTTLE(10, "ignoring %s: %s", active_sub_.getTopic().c_str(), error.c_str());
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    tracker_classes_ = classes;
  }

  std::string save() {
    if (settings_.output.empty() && settings_.cmvision.empty()) {
      return "nowhere to save: start it with _output:=colors.yaml and/or _cmvision:=colors.txt";
    }
    const std::string notice = saveSessionClass(session_, settings_.output, settings_.cmvision);
    ROS_INFO("calibrate_gui: %s", notice.c_str());
    return notice;
  }

  std::string send() {
    if (!session_.result()) return "nothing to send yet: drag a box around the object";
    std::vector<ColorClass> classes;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      classes = tracker_classes_;
    }
    if (classes.empty()) {
      return "no tracker heard on " + active_sub_.getTopic() + ": start the pipeline, or remap " +
             "tracker/active_color_ranges:= to the tracker's topic";
    }
    classes = mergeColorClass(classes, session_.result()->color_class);
    const std::string problem = validateColorClasses(classes);
    if (!problem.empty()) return "not sent: " + problem;
    std_msgs::Header header;
    header.stamp = ros::Time::now();
    ranges_pub_.publish(colorRangesMsg(header, classes));
    return "sent to the tracker on " + ranges_pub_.getTopic() + " (" + std::to_string(classes.size()) + " classes)";
  }

  CalibrateGuiSettings settings_;
  CalibrationSession session_;
  ros::NodeHandle nh_;
  image_transport::ImageTransport it_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber active_sub_;
  ros::Publisher ranges_pub_;
  ErrorThrottle throttle_;
  std::mutex mutex_;
  cv::Mat latest_;
  std::vector<ColorClass> tracker_classes_;
};

}  // namespace rle_vision

int main(int argc, char** argv) {
  ros::init(argc, argv, "calibrate_gui");
  const std::string problem = rle_vision::displayProblem();
  if (!problem.empty()) {
    ROS_FATAL("%s", problem.c_str());
    return 2;
  }
  try {
    rle_vision::CalibrateGui gui(rle_vision::readSettings(ros::NodeHandle("~")));
    gui.run();
  } catch (const std::exception& e) {
    ROS_FATAL("calibrate_gui: %s", e.what());
    return 2;
  }
  return 0;
}
