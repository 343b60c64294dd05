#include "image_conversions.h"

#include <cv_bridge/cv_bridge.h>

namespace rle_vision {

bool viewImageBytes(const sensor_msgs::Image& msg, int type, cv::Mat* mat, std::string* error) {
  // Size first: a huge or empty header must not lead to a huge allocation or a wrapped product.
  *error = checkImageSize(msg.width, msg.height);
  if (!error->empty()) return false;
  const size_t row_bytes = static_cast<size_t>(msg.width) * CV_ELEM_SIZE(type);
  if (msg.step < row_bytes) {
    *error = "image step " + std::to_string(msg.step) + " is smaller than width x bytes per pixel (" +
             std::to_string(row_bytes) + ")";
    return false;
  }
  if (msg.data.size() < static_cast<size_t>(msg.step) * msg.height) {
    *error = "image data has " + std::to_string(msg.data.size()) + " bytes, step x height needs " +
             std::to_string(static_cast<size_t>(msg.step) * msg.height);
    return false;
  }
  *mat = cv::Mat(static_cast<int>(msg.height), static_cast<int>(msg.width), type,
                 const_cast<uint8_t*>(msg.data.data()), msg.step);
  return true;
}

bool viewImage(const sensor_msgs::Image& msg, PixelFormat* format, cv::Mat* mat, std::string* error) {
  if (!pixelFormatFromEncoding(msg.encoding, format)) {
    *error = "unsupported image encoding '" + msg.encoding + "' (supported: " + supportedEncodings() +
             "); Bayer cameras: run the pipeline with debayer:=true (pipeline.launch, play.launch)";
    return false;
  }
  int type = CV_8UC3;
  if (*format == PixelFormat::MONO8) type = CV_8UC1;
  if (*format == PixelFormat::UYVY || *format == PixelFormat::YUYV) type = CV_8UC2;
  if (!viewImageBytes(msg, type, mat, error)) return false;
  *error = checkImage(*mat, *format);
  return error->empty();
}

bool viewCameraImage(const sensor_msgs::Image& msg, const std::string& topic, ErrorThrottle* throttle,
                     CameraFrame* frame, const std::function<void(const std::string&)>& log_error) {
  std::string error;
  if (viewImage(msg, &frame->format, &frame->image, &error)) return true;
  if (throttle->shouldLog(error)) log_error("dropping image on " + topic + ": " + error);
  return false;
}

sensor_msgs::ImagePtr debugImageMsg(const std_msgs::Header& header, const cv::Mat& bgr) {
  return cv_bridge::CvImage(header, "bgr8", bgr).toImageMsg();
}

bool cameraFromInfo(const sensor_msgs::CameraInfo& info, PinholeCamera* camera) {
  camera->width = static_cast<int>(info.width);
  camera->height = static_cast<int>(info.height);
  camera->fx = info.K[0];
  camera->fy = info.K[4];
  camera->cx = info.K[2];
  camera->cy = info.K[5];
  return camera->valid();
}

bool intrinsicsFromInfo(const sensor_msgs::CameraInfo& info, CameraIntrinsics* intrinsics, std::string* error) {
  cameraFromInfo(info, &intrinsics->pinhole);
  intrinsics->distortion_model = info.distortion_model;
  intrinsics->distortion.assign(info.D.begin(), info.D.end());
  *error = validateIntrinsics(*intrinsics);
  return error->empty();
}

}  // namespace rle_vision
