// Where things are: blobs placed on the flat ground (z = 0 of the base frame) through the camera
// model and the camera's pose (the paper's "coordinate transformation based on the fact that the
// ground is level"); attitude_filter.h gives that pose from the horizon when no joint angles
// are known.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "rle_vision/ground/camera_intrinsics.h"
#include "rle_vision/ground/camera_model.h"

namespace rle_vision {

// Where the ray through an ideal pixel meets the ground z = 0. `base_from_optical` is the
// camera's optical frame in the base frame. False (and `reason` says why) when the ray points
// at or above the horizon, the camera is not above the ground, or the point lies beyond
// `max_range_m` (horizontally): such points are rejected, never sent to infinity or behind the
// camera.
bool intersectGround(const Eigen::Isometry3d& base_from_optical, const PinholeCamera& camera, double u, double v,
                     double max_range_m, Eigen::Vector3d* ground, std::string* reason = nullptr);

// The GroundProjector's own options (max_range_m, camera_height_m, attitude_stddev_deg): the
// GROUND and GROUND_ATTITUDE groups of ground_params.def, with their defaults and meanings.
struct GroundOptions {
#define RLE_GROUND_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#define RLE_GROUND_ATTITUDE_PARAM RLE_GROUND_PARAM
#include "rle_vision/params/ground_params.def"
};

struct GroundObstacle {
  Eigen::Vector3d position{0, 0, 0};  // ground contact point, base frame, m (z = 0)
  double width_m = 0;                 // from the blob's box width at that depth
  double height_m = 0;                // of the box's top edge above the contact point (0 if unknown)
  double range_m = 0;                 // horizontal distance from the base frame's origin
  double bearing_rad = 0;             // atan2(y, x), positive to the left
  bool clipped = false;               // the box touches the image's bottom edge: the true contact
                                      // point is out of view, nearer than `position`
  bool occluded = false;              // another blob lies right below the contact pixel: the
                                      // object's bottom may be hidden behind it (see below)
};

// What the projection needs of a blob, in pixels.
struct BlobOutline {
  int left = 0, top = 0, right = 0, bottom = 0;  // bounding box, inclusive
  double contact_x = 0;  // the column where it touches the ground (its centroid's, round(cx))
  int contact_y = 0;     // its lowest row in that column (Region::bottom_at_cx)
};

// The obstacle a blob stands for: its contact point lies below its lowest pixel in the contact
// column (pixel centres are at integers, so at v = contact_y + 0.5), undistorted and
// intersected with the ground. That pixel is on the object's bottom outline, so it stays on
// the object's footprint whatever the camera's roll or the object's yaw. Width: the box's
// width at the contact point's depth; height: where the ray through the top edge passes the
// vertical above the contact point. False with `reason` when it cannot be placed.
bool projectBlobToGround(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& base_from_optical,
                         const BlobOutline& blob, double max_range_m, GroundObstacle* obstacle,
                         std::string* reason = nullptr);

// Whether another blob's box holds a pixel within `gap_px` rows right below blob `index`'s
// contact pixel. The object's bottom may then be hidden behind that blob, and its true contact
// point lie nearer than the projection (but beyond the other object).
bool contactMayBeHidden(const std::vector<BlobOutline>& blobs, size_t index, int gap_px = 2);

// The camera's optical frame in the base frame for a camera body (REP 103: x forward, z up)
// with this roll, pitch (positive nose down) and yaw, `height_m` above the base frame's origin.
Eigen::Isometry3d baseFromOptical(double roll, double pitch, double yaw, double height_m);

}  // namespace rle_vision
