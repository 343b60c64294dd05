#include "conversions.h"

#include <algorithm>
#include <cmath>

#include <cv_bridge/cv_bridge.h>

namespace rle_vision {

bool viewImage(const sensor_msgs::Image& msg, PixelFormat* format, cv::Mat* mat, std::string* error) {
  if (!pixelFormatFromEncoding(msg.encoding, format)) {
    *error = "unsupported image encoding '" + msg.encoding + "' (supported: " + supportedEncodings() +
             "); convert it first, e.g. with image_proc for Bayer images";
    return false;
  }
  // Size first: a huge or empty header must not lead to a huge allocation or a wrapped product.
  *error = checkImageSize(msg.width, msg.height);
  if (!error->empty()) return false;
  int type = CV_8UC3;
  if (*format == PixelFormat::MONO8) type = CV_8UC1;
  if (*format == PixelFormat::UYVY || *format == PixelFormat::YUYV) type = CV_8UC2;
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
  *error = checkImage(*mat, *format);
  return error->empty();
}

bool colorClassesFromMsg(const ColorRangeArray& msg, std::vector<ColorClass>* classes, std::string* error) {
  classes->clear();
  for (const ColorRange& r : msg.ranges) {
    ColorClass c;
    c.name = r.name;
    if (!parseColorSpace(r.space, &c.space)) {
      *error = "colour range '" + r.name + "' has unknown space '" + r.space + "' (use YUV, RGB or HSV)";
      return false;
    }
    for (int ch = 0; ch < 3; ++ch) {
      c.min[ch] = r.min[ch];
      c.max[ch] = r.max[ch];
      c.display_rgb[ch] = r.display_rgb[ch];
    }
    c.min_area_px = std::max<uint32_t>(1, r.min_area);
    c.source = r.source.empty() ? "config" : r.source;
    classes->push_back(c);
  }
  *error = validateColorClasses(*classes);
  return error->empty();
}

ColorRange colorRangeToMsg(const ColorClass& c) {
  ColorRange r;
  r.name = c.name;
  r.space = toString(c.space);
  for (int ch = 0; ch < 3; ++ch) {
    r.min[ch] = c.min[ch];
    r.max[ch] = c.max[ch];
    r.display_rgb[ch] = c.display_rgb[ch];
  }
  r.min_area = c.min_area_px;
  r.source = c.source;
  return r;
}

Blob blobToMsg(const TrackedBlob& blob, const std::string& color_name) {
  Blob b;
  const Region& r = blob.region;
  b.id = blob.id;
  b.color = color_name;
  b.area = r.area;
  b.cx = static_cast<float>(r.cx);
  b.cy = static_cast<float>(r.cy);
  b.left = static_cast<uint32_t>(r.left);
  b.top = static_cast<uint32_t>(r.top);
  b.right = static_cast<uint32_t>(r.right);
  b.bottom = static_cast<uint32_t>(r.bottom);
  b.bottom_at_cx = static_cast<uint32_t>(r.bottom_at_cx);
  b.vx = static_cast<float>(blob.vx);
  b.vy = static_cast<float>(blob.vy);
  b.angle = static_cast<float>(r.angle);
  b.age = blob.age;
  return b;
}

Line lineToMsg(const ImageLine& line, double x1, double y1, double x2, double y2, uint32_t votes, uint32_t support) {
  Line l;
  l.theta = static_cast<float>(line.theta);
  l.intercept = static_cast<float>(line.intercept);
  l.x1 = static_cast<float>(x1);
  l.y1 = static_cast<float>(y1);
  l.x2 = static_cast<float>(x2);
  l.y2 = static_cast<float>(y2);
  l.votes = votes;
  l.support = support;
  return l;
}

LandmarkOptions optionsFromConfig(const LandmarkConfig& c) {
  LandmarkOptions o;
  o.objects.gray_threshold = static_cast<uint8_t>(c.gray_threshold);
  o.objects.sharp_threshold = static_cast<uint8_t>(c.sharp_threshold);
  o.objects.min_object_px = static_cast<uint32_t>(c.min_object_px);
  o.objects.thin = c.thin_edges;
  o.hough.min_votes = c.min_votes;
  o.hough.min_line_length_px = c.min_line_length_px;
  o.hough.sampling_margin = c.sampling_margin;
  o.hough.max_samples_per_object = c.max_samples_per_object;
  o.hough.max_rounds = c.max_rounds;
  o.hough.max_failed_peaks = c.max_failed_peaks;
  o.hough.min_pair_distance_px = c.min_pair_distance_px;
  o.hough.theta_bin_deg = c.theta_bin_deg;
  o.hough.intercept_bin_px = c.intercept_bin_px;
  o.hough.peak_angle_deg = c.peak_angle_deg;
  o.hough.peak_distance_px = c.peak_distance_px;
  o.hough.fit_distance_px = c.fit_distance_px;
  o.hough.max_gap_px = c.max_gap_px;
  o.hough.min_support_ratio = c.min_support_ratio;
  o.hough.seed = static_cast<uint64_t>(c.seed);
  o.horizon.min_piece_length_px = c.horizon_min_piece_px;
  o.horizon.max_angle_deg = c.horizon_max_angle_deg;
  o.horizon.merge_angle_deg = c.horizon_merge_angle_deg;
  o.horizon.merge_distance_px = c.horizon_merge_distance_px;
  o.horizon.min_coverage = c.horizon_min_coverage;
  return o;
}

LearningOptions learningFromConfig(const LandmarkConfig& c) {
  LearningOptions o;
  o.blend = c.learning_blend;
  o.match_gate = c.learning_match_gate;
  o.max_sigma = c.learning_max_sigma;
  o.mode_radius = c.learning_mode_radius;
  o.min_region_px = static_cast<uint32_t>(c.learning_min_region_px);
  o.shrink_px = c.learning_shrink_px;
  o.horizon_margin_px = c.learning_horizon_margin_px;
  o.stale_after_s = c.learning_stale_after_s;
  o.create_classes = c.learning_create_classes;
  o.persist_frames = c.learning_persist_frames;
  o.min_new_class_px = static_cast<uint32_t>(c.learning_min_new_class_px);
  return o;
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

CmvisionBlobs cmvisionBlobsMsg(const BlobArray& blobs, const ColorTable& table) {
  CmvisionBlobs out;
  out.header = blobs.header;
  out.image_width = blobs.image_width;
  out.image_height = blobs.image_height;
  std::vector<std::pair<int, const Blob*>> ordered;
  for (const Blob& b : blobs.blobs) ordered.emplace_back(table.indexOf(b.color), &b);
  std::stable_sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second->area > b.second->area;
  });
  for (const auto& entry : ordered) {
    const Blob& b = *entry.second;
    CmvisionBlob c;
    c.name = b.color;
    if (entry.first >= 0) {
      const Channels& rgb = table.classes()[entry.first].display_rgb;
      c.red = rgb[0];
      c.green = rgb[1];
      c.blue = rgb[2];
    }
    c.area = b.area;
    c.x = static_cast<uint32_t>(std::rint(b.cx + 0.5));  // cmvision's rounding, kept for drop-in use
    c.y = static_cast<uint32_t>(std::rint(b.cy + 0.5));
    c.left = b.left;
    c.right = b.right;
    c.top = b.top;
    c.bottom = b.bottom;
    out.blobs.push_back(c);
  }
  out.blob_count = static_cast<uint32_t>(out.blobs.size());
  return out;
}

bool intrinsicsFromInfo(const sensor_msgs::CameraInfo& info, CameraIntrinsics* intrinsics, std::string* error) {
  cameraFromInfo(info, &intrinsics->pinhole);
  intrinsics->distortion_model = info.distortion_model;
  intrinsics->distortion.assign(info.D.begin(), info.D.end());
  *error = validateIntrinsics(*intrinsics);
  return error->empty();
}

AttitudeFilterOptions attitudeFilterFromConfig(const GroundProjectorConfig& config) {
  AttitudeFilterOptions o;
  o.smoothing = config.attitude_smoothing;
  o.min_confidence = config.horizon_min_confidence;
  o.max_jump_deg = config.attitude_max_jump_deg;
  o.max_rejected = config.attitude_max_rejected;
  o.max_hold_s = config.attitude_max_hold_s;
  return o;
}

}  // namespace rle_vision
