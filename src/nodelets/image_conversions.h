// sensor_msgs images and camera_info to the core's views and camera models, and back.
#pragma once

#include <string>

#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "rle_vision/camera_intrinsics.h"
#include "rle_vision/camera_model.h"
#include "rle_vision/pixel_format.h"

namespace rle_vision {

// A zero-copy cv::Mat view of an image message (like cv_bridge::toCvShare, which would reject
// yuv422_yuy2 on older cv_bridge versions), after checking the encoding, the step and the
// data size. On failure returns false and says why in `error`; the message must outlive `mat`.
bool viewImage(const sensor_msgs::Image& msg, PixelFormat* format, cv::Mat* mat, std::string* error);
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
