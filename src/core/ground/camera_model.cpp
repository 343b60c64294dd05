#include "rle_vision/ground/camera_model.h"

#include <cmath>

#include <Eigen/Geometry>

namespace rle_vision {

PinholeCamera PinholeCamera::fromHorizontalFov(int width, int height, double hfov_rad) {
  PinholeCamera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = 0.5 * width / std::tan(0.5 * hfov_rad);
  camera.cx = 0.5 * width;
  camera.cy = 0.5 * height;
  return camera;
}

bool PinholeCamera::valid() const {
  return width > 0 && height > 0 && std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0 &&
         std::isfinite(cx) && std::isfinite(cy);
}

Eigen::Matrix3d opticalToBodyRotation() {
  Eigen::Matrix3d m;
  // Columns: optical x (right) = -body y, optical y (down) = -body z, optical z = body x.
  m << 0, 0, 1,
      -1, 0, 0,
      0, -1, 0;
  return m;
}

Eigen::Matrix3d opticalToBaseRotation(double roll, double pitch, double yaw) {
  const Eigen::Matrix3d body = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  return body * opticalToBodyRotation();
}

bool horizonFromUp(const PinholeCamera& camera, const Eigen::Vector3d& up, double* a, double* b,
                   double* c) {
  // up . K^-1 (u, v, 1) = 0.
  *a = up.x() / camera.fx;
  *b = up.y() / camera.fy;
  *c = up.z() - up.x() * camera.cx / camera.fx - up.y() * camera.cy / camera.fy;
  return std::hypot(*a, *b) > 1e-12;
}

void attitudeFromHorizon(const PinholeCamera& camera, const ImageLine& horizon, double* roll,
                         double* pitch) {
  double a = 0, b = 0, c = 0;
  homogeneousFromLine(horizon, &a, &b, &c);
  // The ground's up vector in the optical frame is K^T l (up to scale and sign).
  Eigen::Vector3d up(camera.fx * a, camera.fy * b, camera.cx * a + camera.cy * b + c);
  up.normalize();
  if (up.y() > 0) up = -up;  // up points to the top of the image while |roll| < 90 deg
  // up_optical = (-sin r cos p, -cos r cos p, -sin p).
  *pitch = std::asin(std::max(-1.0, std::min(1.0, -up.z())));
  *roll = std::atan2(-up.x(), -up.y());
}

}  // namespace rle_vision
