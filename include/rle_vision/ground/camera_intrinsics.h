// A camera's intrinsics with its lens distortion (camera_info's K, distortion model and D), and
// undistorting pixels with them.
#pragma once

#include <string>
#include <vector>

#include "rle_vision/ground/camera_model.h"

namespace rle_vision {

// A camera_info's intrinsics with its distortion model (ROS names).
struct CameraIntrinsics {
  PinholeCamera pinhole;
  std::string distortion_model;   // "plumb_bob", "rational_polynomial", "equidistant" or "" (none)
  std::vector<double> distortion;  // D; all zero (or empty) means none
};

// Reason the intrinsics cannot be used, or "" when they are fine.
std::string validateIntrinsics(const CameraIntrinsics& intrinsics);

// The ideal (undistorted) pixel seen at a raw image pixel. Returns false when the undistortion
// does not converge to a finite point.
bool undistortPixel(const CameraIntrinsics& intrinsics, double u, double v, double* u_ideal, double* v_ideal);

}  // namespace rle_vision
