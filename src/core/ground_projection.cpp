#include "rle_vision/ground_projection.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace rle_vision {
namespace {

bool allZero(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double d) { return d == 0.0; });
}

void setReason(std::string* reason, const char* text) {
  if (reason) *reason = text;
}

}  // namespace

std::string validateIntrinsics(const CameraIntrinsics& intrinsics) {
  if (!intrinsics.pinhole.valid()) {
    return "camera_info has no usable intrinsics (width, height, fx, fy must be positive, K finite); "
           "is the camera calibrated?";
  }
  for (double d : intrinsics.distortion) {
    if (!std::isfinite(d)) return "camera_info's distortion coefficients D hold a NaN or infinity";
  }
  if (allZero(intrinsics.distortion)) return "";
  const std::string& model = intrinsics.distortion_model;
  const size_t n = intrinsics.distortion.size();
  if (model == "plumb_bob" || model == "rational_polynomial") {
    if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14) {
      return "camera_info's " + model + " distortion has " + std::to_string(n) + " coefficients (expected 4, 5, 8, 12 or 14)";
    }
    return "";
  }
  if (model == "equidistant") {
    if (n != 4) return "camera_info's equidistant distortion has " + std::to_string(n) + " coefficients (expected 4)";
    return "";
  }
  return "camera_info's distortion model '" + model +
         "' is not supported (plumb_bob, rational_polynomial, equidistant; or all-zero D)";
}

bool undistortPixel(const CameraIntrinsics& intrinsics, double u, double v, double* u_ideal, double* v_ideal) {
  const PinholeCamera& c = intrinsics.pinhole;
  if (intrinsics.distortion.empty() || allZero(intrinsics.distortion)) {
    *u_ideal = u;
    *v_ideal = v;
    return std::isfinite(u) && std::isfinite(v);
  }
  const cv::Matx33d k(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const std::vector<cv::Point2d> raw{{u, v}};
  std::vector<cv::Point2d> ideal;
  if (intrinsics.distortion_model == "equidistant") {
    cv::fisheye::undistortPoints(raw, ideal, k, cv::Mat(intrinsics.distortion), cv::noArray(), k);
  } else {
    // OpenCV iterates; a fixed count with a tight epsilon keeps strong distortion accurate.
    cv::undistortPoints(raw, ideal, k, cv::Mat(intrinsics.distortion), cv::noArray(), k,
                        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-10));
  }
  *u_ideal = ideal[0].x;
  *v_ideal = ideal[0].y;
  return std::isfinite(*u_ideal) && std::isfinite(*v_ideal);
}

bool intersectGround(const Eigen::Isometry3d& base_from_optical, const PinholeCamera& camera, double u, double v,
                     double max_range_m, Eigen::Vector3d* ground, std::string* reason) {
  const Eigen::Vector3d origin = base_from_optical.translation();
  if (!(origin.z() > 0)) {
    setReason(reason, "the camera is not above the ground (z <= 0 in the base frame)");
    return false;
  }
  const Eigen::Vector3d direction = base_from_optical.linear() * camera.ray(u, v);
  // The ray must descend; a ray at or above the horizon never meets the ground in front.
  const double descent = -direction.z() / direction.head<2>().norm();
  if (!(descent > 1e-9)) {
    setReason(reason, "the point is at or above the horizon");
    return false;
  }
  const double t = origin.z() / -direction.z();
  const Eigen::Vector3d point = origin + t * direction;
  if (!(point.head<2>().norm() <= max_range_m)) {
    setReason(reason, "the point is beyond max_range_m");
    return false;
  }
  *ground = Eigen::Vector3d(point.x(), point.y(), 0.0);
  return true;
}

bool projectBlobToGround(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& base_from_optical,
                         const BlobOutline& blob, double max_range_m, GroundObstacle* obstacle, std::string* reason) {
  const int left = blob.left, right = blob.right;
  const double u = blob.contact_x, v = blob.contact_y + 0.5;
  double ui = 0, vi = 0;
  if (!undistortPixel(intrinsics, u, v, &ui, &vi)) {
    setReason(reason, "the pixel could not be undistorted");
    return false;
  }
  Eigen::Vector3d ground;
  if (!intersectGround(base_from_optical, intrinsics.pinhole, ui, vi, max_range_m, &ground, reason)) return false;
  obstacle->position = ground;
  obstacle->range_m = ground.head<2>().norm();
  obstacle->bearing_rad = std::atan2(ground.y(), ground.x());
  obstacle->clipped = blob.contact_y >= intrinsics.pinhole.height - 1;
  // The box's edges, undistorted on the contact row, span this width at the contact point's depth.
  double ul = 0, vl = 0, ur = 0, vr = 0;
  const double depth = (base_from_optical.inverse() * ground).z();
  if (undistortPixel(intrinsics, left - 0.5, v, &ul, &vl) && undistortPixel(intrinsics, right + 0.5, v, &ur, &vr)) {
    obstacle->width_m = std::abs(ur - ul) * depth / intrinsics.pinhole.fx;
  } else {
    obstacle->width_m = (right - left + 1) * depth / intrinsics.pinhole.fx;
  }
  // Height: the point of the vertical line ground + s z nearest the ray through the top edge.
  obstacle->height_m = 0;
  double ut = 0, vt = 0;
  if (undistortPixel(intrinsics, u, blob.top - 0.5, &ut, &vt)) {
    const Eigen::Vector3d origin = base_from_optical.translation();
    const Eigen::Vector3d d = base_from_optical.linear() * intrinsics.pinhole.ray(ut, vt);
    const Eigen::Vector3d w0 = ground - origin;
    const double b = d.z(), c = d.dot(d), e = d.dot(w0);
    const double denominator = c - b * b;  // 0 only for a vertical ray
    if (denominator > 1e-12) obstacle->height_m = std::max(0.0, (b * e - c * w0.z()) / denominator);
  }
  return true;
}

bool contactMayBeHidden(const std::vector<BlobOutline>& blobs, size_t index, int gap_px) {
  const BlobOutline& blob = blobs[index];
  const int column = static_cast<int>(std::lround(blob.contact_x));
  for (size_t j = 0; j < blobs.size(); ++j) {
    const BlobOutline& other = blobs[j];
    if (j == index || column < other.left || column > other.right) continue;
    if (other.top <= blob.contact_y + gap_px && other.bottom > blob.contact_y) return true;
  }
  return false;
}

Eigen::Isometry3d baseFromOptical(double roll, double pitch, double yaw, double height_m) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = opticalToBaseRotation(roll, pitch, yaw);
  pose.translation() = Eigen::Vector3d(0, 0, height_m);
  return pose;
}

std::string validateAttitudeFilterOptions(const AttitudeFilterOptions& o) {
  if (!std::isfinite(o.smoothing) || o.smoothing < 0 || o.smoothing >= 1) return "smoothing must be in [0, 1)";
  if (!std::isfinite(o.min_confidence) || o.min_confidence < 0 || o.min_confidence > 1) {
    return "min_confidence must be in [0, 1]";
  }
  if (!std::isfinite(o.max_jump_deg) || o.max_jump_deg <= 0) return "max_jump_deg must be positive";
  if (o.max_rejected < 1) return "max_rejected must be at least 1";
  if (!std::isfinite(o.max_hold_s) || o.max_hold_s <= 0) return "max_hold_s must be positive";
  return "";
}

AttitudeFilter::Outcome AttitudeFilter::update(bool found, double roll, double pitch, double confidence,
                                               double stamp_s) {
  if (initialised_ && stamp_s <= last_stamp_s_) return Outcome::kNoHorizon;  // old or repeated
  if (!found || !std::isfinite(roll) || !std::isfinite(pitch)) return Outcome::kNoHorizon;
  if (!(confidence >= options_.min_confidence)) return Outcome::kLowConfidence;
  const bool restart = !initialised_ || stamp_s - last_accepted_s_ > options_.max_hold_s;
  if (restart) {
    roll_ = roll;
    pitch_ = pitch;
    roll_rate_ = pitch_rate_ = 0;
  } else {
    const double dt = stamp_s - last_stamp_s_;
    const double roll_predicted = roll_ + roll_rate_ * dt, pitch_predicted = pitch_ + pitch_rate_ * dt;
    const double roll_residual = roll - roll_predicted, pitch_residual = pitch - pitch_predicted;
    const double max_jump = options_.max_jump_deg * M_PI / 180;
    if ((std::abs(roll_residual) > max_jump || std::abs(pitch_residual) > max_jump) &&
        ++rejected_in_a_row_ < options_.max_rejected) {
      return Outcome::kJump;
    }
    if (rejected_in_a_row_ >= options_.max_rejected) {  // the glitch persists: it is the truth now
      roll_ = roll;
      pitch_ = pitch;
      roll_rate_ = pitch_rate_ = 0;
    } else {
      // Alpha-beta filter; beta = alpha^2 / (2 - alpha) damps it critically (alpha = 1: no smoothing).
      const double alpha = 1.0 - options_.smoothing, beta = alpha * alpha / (2.0 - alpha);
      roll_ = roll_predicted + alpha * roll_residual;
      pitch_ = pitch_predicted + alpha * pitch_residual;
      roll_rate_ += beta * roll_residual / dt;
      pitch_rate_ += beta * pitch_residual / dt;
    }
  }
  rejected_in_a_row_ = 0;
  initialised_ = true;
  last_stamp_s_ = last_accepted_s_ = stamp_s;
  return Outcome::kAccepted;
}

bool AttitudeFilter::valid(double stamp_s) const {
  return initialised_ && std::abs(stamp_s - last_accepted_s_) <= options_.max_hold_s;
}

}  // namespace rle_vision
