// Conversions between rle_vision messages / sensor_msgs and the ROS-free core types.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "rle_vision/Blob.h"
#include "rle_vision/BlobArray.h"
#include "rle_vision/CmvisionBlobs.h"
#include "rle_vision/GroundProjectorConfig.h"
#include "rle_vision/LandmarkConfig.h"
#include "rle_vision/ColorRangeArray.h"
#include "rle_vision/Line.h"
#include "rle_vision/blob_tracker.h"
#include "rle_vision/camera_model.h"
#include "rle_vision/color_class.h"
#include "rle_vision/color_table.h"
#include "rle_vision/color_learning.h"
#include "rle_vision/ground_projection.h"
#include "rle_vision/landmark_detector.h"
#include "rle_vision/line_geometry.h"
#include "rle_vision/pixel_format.h"

namespace rle_vision {

// A zero-copy cv::Mat view of an image message (like cv_bridge::toCvShare, which would reject
// yuv422_yuy2 on older cv_bridge versions), after checking the encoding, the step and the
// data size. On failure returns false and says why in `error`; the message must outlive `mat`.
bool viewImage(const sensor_msgs::Image& msg, PixelFormat* format, cv::Mat* mat, std::string* error);

// Colour classes from a ColorRangeArray; false (with the reason) if any entry is invalid.
bool colorClassesFromMsg(const ColorRangeArray& msg, std::vector<ColorClass>* classes, std::string* error);
ColorRange colorRangeToMsg(const ColorClass& c);

Blob blobToMsg(const TrackedBlob& blob, const std::string& color_name);

// The blobs in cmvision's message shape (cmvision/Blobs), ordered as cmvision orders them: by
// class, then by area (largest first); colours are the classes' display colours.
CmvisionBlobs cmvisionBlobsMsg(const BlobArray& blobs, const ColorTable& table);
Line lineToMsg(const ImageLine& line, double x1, double y1, double x2, double y2, uint32_t votes, uint32_t support);

// The Landmark nodelet's dynamic parameters as core options (edge_gain belongs to the
// EdgeDetector and keeps its default).
LandmarkOptions optionsFromConfig(const LandmarkConfig& config);

// The Landmark nodelet's colour-learning parameters as core options.
LearningOptions learningFromConfig(const LandmarkConfig& config);

// A bgr8 image message (copied) with the given header.
sensor_msgs::ImagePtr debugImageMsg(const std_msgs::Header& header, const cv::Mat& bgr);

// The pinhole model of a camera_info (K only); false when K is unusable.
bool cameraFromInfo(const sensor_msgs::CameraInfo& info, PinholeCamera* camera);

// K, the distortion model and D of a camera_info; false (with the reason) when unusable.
bool intrinsicsFromInfo(const sensor_msgs::CameraInfo& info, CameraIntrinsics* intrinsics, std::string* error);

// The GroundProjector's attitude filter parameters as core options.
AttitudeFilterOptions attitudeFilterFromConfig(const GroundProjectorConfig& config);

}  // namespace rle_vision
