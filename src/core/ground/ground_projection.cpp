#include "rle_vision/ground/ground_projection.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {
namespace {

void setReason(std::string* reason, const char* text) {
  if (reason) *reason = text;
}

}  // namespace

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

}  // namespace rle_vision
