// Pinhole camera and camera attitude (REP 103: camera body x forward, y left, z up; optical
// frame x right, y down, z forward).
#pragma once

#include <Eigen/Core>

#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {

struct PinholeCamera {
  int width = 0, height = 0;  // px
  double fx = 0, fy = 0;      // focal lengths, px
  double cx = 0, cy = 0;      // principal point, px

  static PinholeCamera fromHorizontalFov(int width, int height, double hfov_rad);
  bool valid() const;
  // Pixel of a point given in the optical frame (z > 0).
  Eigen::Vector2d project(const Eigen::Vector3d& p_optical) const {
    return {fx * p_optical.x() / p_optical.z() + cx, fy * p_optical.y() / p_optical.z() + cy};
  }
  // Direction of the ray through a pixel, optical frame, z = 1.
  Eigen::Vector3d ray(double u, double v) const { return {(u - cx) / fx, (v - cy) / fy, 1.0}; }
};

// Rotation taking optical-frame vectors to the level base frame, for a camera body with
// roll, pitch (positive = nose down) and yaw, applied as R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d opticalToBaseRotation(double roll, double pitch, double yaw);
// The fixed rotation from the optical frame to the camera body frame.
Eigen::Matrix3d opticalToBodyRotation();

// Horizon of a level ground plane: the image line of rays parallel to the ground.
// `up_optical` is the base frame's +z expressed in the optical frame. Pixels with
// (a, b, c) . (u, v, 1) > 0 see the sky. Returns false when the camera looks straight up
// or down (no horizon line exists).
bool horizonFromUp(const PinholeCamera& camera, const Eigen::Vector3d& up_optical, double* a,
                   double* b, double* c);

// Camera roll and pitch (REP 103) from the horizon line. Assumes |roll| < 90 deg.
void attitudeFromHorizon(const PinholeCamera& camera, const ImageLine& horizon, double* roll,
                         double* pitch);

}  // namespace rle_vision
