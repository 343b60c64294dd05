#include "rle_vision/ground/camera_intrinsics.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace rle_vision {
namespace {

bool allZero(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double d) { return d == 0.0; });
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

}  // namespace rle_vision
