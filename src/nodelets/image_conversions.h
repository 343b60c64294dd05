// sensor_msgs images and camera_info to the core's views and camera models, and back.
#pragma once

#include <functional>
#include <string>

#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "rle_vision/ground/camera_intrinsics.h"
#include "rle_vision/ground/camera_model.h"
#include "rle_vision/color/pixel_format.h"

#include "error_throttle.h"

namespace rle_vision {

// A zero-copy cv::Mat view of an image message (like cv_bridge::toCvShare, which would reject
// yuv422_yuy2 on older cv_bridge versions), after checking the encoding, the step and the
// data size. On failure returns false and says why in `error`; the message must outlive `mat`.
bool viewImage(const sensor_msgs::Image& msg, PixelFormat* format, cv::Mat* mat, std::string* error);
// A camera frame's pixels: a zero-copy view and its layout.
struct CameraFrame {
  PixelFormat format = PixelFormat::BGR8;
  cv::Mat image;
};

// viewImage for a camera frame a nodelet drops when it is bad: on failure `log_error` gets
// "dropping image on TOPIC: REASON" when `throttle` lets that problem be logged now (the
// nodelet's own logging, so that the message names its source file).
bool viewCameraImage(const sensor_msgs::Image& msg, const std::string& topic, ErrorThrottle* throttle,
                     CameraFrame* frame, const std::function<void(const std::string&)>& log_error);
// The byte-layout part of viewImage for a known OpenCV type (e.g. CV_8UC1 for a Bayer mosaic):
// size limits, step and data length checked, then a zero-copy view.
bool viewImageBytes(const sensor_msgs::Image& msg, int type, cv::Mat* mat, std::string* error);

// A bgr8 image message (copied) with the given header.
sensor_msgs::ImagePtr debugImageMsg(const std_msgs::Header& header, const cv::Mat& bgr);

// The pinhole model of a camera_info (K only); false when K is unusable.
bool cameraFromInfo(const sensor_msgs::CameraInfo& info, PinholeCamera* camera);

// K, the distortion model and D of a camera_info; false (with the reason) when unusable.
bool intrinsicsFromInfo(const sensor_msgs::CameraInfo& info, CameraIntrinsics* intrinsics, std::string* error);

}  // namespace rle_vision
