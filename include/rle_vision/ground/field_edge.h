// The field boundary on the ground: where the floor ends, in metres around the robot (the
// nearest field edge per bearing), from the image polyline the field stage finds and the
// camera's pose, on the flat ground the GroundProjector assumes.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "rle_vision/ground/camera_intrinsics.h"

namespace rle_vision {

struct FieldEdgeOnGround {
  // Where the image polyline meets the ground, base frame (z = 0), left to right in the image.
  std::vector<Eigen::Vector3d> points;
  // Per bearing bin (bearing_min_rad + i bearing_step_rad, positive to the left; bins aligned
  // to multiples of the step so that frames share them; contiguous across +-pi, so that a
  // camera looking backwards may give bearings beyond pi): the nearest edge point's horizontal
  // range (m); +infinity where no edge point falls (REP 117: no return).
  double bearing_min_rad = 0;
  double bearing_step_rad = 0;
  std::vector<float> ranges_m;
};

// Samples the boundary's polyline (left to right, as FieldBoundary carries it: x, and the row of
// the field's topmost pixel; the edge itself lies on that pixel's upper side, half a pixel
// above) every `step_px` columns and at its ends, undistorts each sample and intersects its ray with the ground; samples at or above
// the horizon, or beyond max_range_m, and non-finite or absurdly wide pieces are left out. Then the nearest point per bearing bin of
// `bearing_step_rad`. An empty polyline or no point on the ground gives no points and no bins.
FieldEdgeOnGround projectFieldEdge(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& base_from_optical,
                                   const std::vector<Eigen::Vector2d>& polyline, double max_range_m,
                                   double bearing_step_rad, double step_px = 1.0);

}  // namespace rle_vision
