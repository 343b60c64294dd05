// Ground plane: back-projection geometry with known answers, distortion, blob placement against
// the simulator's exact box footprints (true pose and pose from the horizon), attitude filter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <opencv2/calib3d.hpp>

#include "rle_vision/ground/attitude_filter.h"
#include "rle_vision/ground/ground_projection.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/sim/scene_simulator.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;

CameraIntrinsics vgaIntrinsics() {
  CameraIntrinsics intrinsics;
  intrinsics.pinhole = PinholeCamera::fromHorizontalFov(640, 480, 70 * kDeg);
  return intrinsics;
}

// The pixel of a base-frame point seen by a camera with this pose.
Eigen::Vector2d pixelOf(const PinholeCamera& camera, const Eigen::Isometry3d& base_from_optical, const Eigen::Vector3d& p) {
  return camera.project(base_from_optical.inverse() * p);
}

BlobOutline outline(int left, int top, int right, int bottom) {
  BlobOutline b;
  b.left = left;
  b.top = top;
  b.right = right;
  b.bottom = bottom;
  b.contact_x = 0.5 * (left + right);
  b.contact_y = bottom;
  return b;
}

// A box's outline from the label image: its contact column is its centroid's.
BlobOutline truthOutline(const SimFrame& f, const BoxTruth& box) {
  BlobOutline b = outline(box.left, box.top, box.right, box.bottom);
  b.contact_x = box.cx;
  const int column = static_cast<int>(std::lround(box.cx));
  for (int y = box.bottom; y >= box.top; --y) {
    if (f.labels.at<uint8_t>(y, column) == box.label) {
      b.contact_y = y;
      break;
    }
  }
  return b;
}

TEST(GroundProjection, CameraLookingStraightDown) {
  const CameraIntrinsics c = vgaIntrinsics();
  const Eigen::Isometry3d pose = baseFromOptical(0, 90 * kDeg, 0, 2.0);
  Eigen::Vector3d g;
  ASSERT_TRUE(intersectGround(pose, c.pinhole, c.pinhole.cx, c.pinhole.cy, 100, &g));
  EXPECT_NEAR(g.x(), 0, 1e-9);
  EXPECT_NEAR(g.y(), 0, 1e-9);
  EXPECT_EQ(g.z(), 0);
  // Half a focal length right of centre: 1 m to the right (-y) of the foot point at 2 m height.
  ASSERT_TRUE(intersectGround(pose, c.pinhole, c.pinhole.cx + 0.5 * c.pinhole.fx, c.pinhole.cy, 100, &g));
  EXPECT_NEAR(g.x(), 0, 1e-9);
  EXPECT_NEAR(g.y(), -1.0, 1e-9);
  // Half a focal length down the image: the top of the image faces forward, so 1 m behind.
  ASSERT_TRUE(intersectGround(pose, c.pinhole, c.pinhole.cx, c.pinhole.cy + 0.5 * c.pinhole.fy, 100, &g));
  EXPECT_NEAR(g.x(), -1.0, 1e-9);
  EXPECT_NEAR(g.y(), 0, 1e-9);
}

TEST(GroundProjection, TiltedCameraRowsMapToKnownDistances) {
  const CameraIntrinsics c = vgaIntrinsics();
  const double height = 0.45, pitch = 20 * kDeg;
  const Eigen::Isometry3d pose = baseFromOptical(0, pitch, 0, height);
  for (double v : {240.0, 300.0, 400.0, 479.5}) {
    Eigen::Vector3d g;
    ASSERT_TRUE(intersectGround(pose, c.pinhole, c.pinhole.cx, v, 100, &g));
    const double below_axis = std::atan((v - c.pinhole.cy) / c.pinhole.fy);
    EXPECT_NEAR(g.x(), height / std::tan(pitch + below_axis), 1e-9) << "row " << v;
    EXPECT_NEAR(g.y(), 0, 1e-9);
  }
}

TEST(GroundProjection, RolledAndYawedCamerasRoundTripGroundPoints) {
  const CameraIntrinsics c = vgaIntrinsics();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-15, 15), forward(0.3, 6), side(-2, 2);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Isometry3d pose = baseFromOptical(angle(rng) * kDeg, (20 + angle(rng)) * kDeg, angle(rng) * kDeg, 0.45);
    const Eigen::Vector3d truth(forward(rng), side(rng), 0);
    const Eigen::Vector3d in_camera = pose.inverse() * truth;
    if (in_camera.z() <= 0) continue;
    const Eigen::Vector2d px = c.pinhole.project(in_camera);
    Eigen::Vector3d g;
    ASSERT_TRUE(intersectGround(pose, c.pinhole, px.x(), px.y(), 100, &g));
    EXPECT_LT((g - truth).norm(), 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

TEST(GroundProjection, PointsAtOrAboveTheHorizonAreRejectedNotSentToInfinity) {
  const CameraIntrinsics c = vgaIntrinsics();
  const double roll = 8 * kDeg, pitch = 10 * kDeg;
  const Eigen::Isometry3d pose = baseFromOptical(roll, pitch, 0, 0.45);
  double a, b, h;
  ASSERT_TRUE(horizonFromUp(c.pinhole, pose.linear().transpose() * Eigen::Vector3d::UnitZ(), &a, &b, &h));
  const double norm = std::hypot(a, b);
  // Walk along the image's middle column across the horizon (sky where a u + b v + h > 0).
  const double u = 320;
  const double v_horizon = -(a * u + h) / b;
  std::string reason;
  Eigen::Vector3d g;
  for (double offset_px : {-50.0, -1.0, -1e-3, 0.0}) {  // towards the sky and on the line
    const double v = v_horizon + offset_px * (b > 0 ? -1 : 1);
    EXPECT_GE((a * u + b * v + h) / norm, -1e-9);
    EXPECT_FALSE(intersectGround(pose, c.pinhole, u, v, 1e9, &g, &reason)) << offset_px;
    EXPECT_EQ(reason, "the point is at or above the horizon");
  }
  // Just below the horizon the point is far in front of the camera, never behind it.
  const double v_below = v_horizon + (b > 0 ? -1 : 1) * 0.5;
  ASSERT_TRUE(intersectGround(pose, c.pinhole, u, v_below, 1e9, &g));
  EXPECT_GT(g.x(), 20);
  EXPECT_FALSE(intersectGround(pose, c.pinhole, u, v_below, 10, &g, &reason));
  EXPECT_EQ(reason, "the point is beyond max_range_m");
  // A camera looking up sees no ground at the image centre; one below the ground sees none at all.
  EXPECT_FALSE(intersectGround(baseFromOptical(0, -30 * kDeg, 0, 0.45), c.pinhole, 320, 240, 1e9, &g));
  EXPECT_FALSE(intersectGround(baseFromOptical(0, 60 * kDeg, 0, -0.1), c.pinhole, 320, 240, 1e9, &g, &reason));
  EXPECT_EQ(reason, "the camera is not above the ground (z <= 0 in the base frame)");
}

TEST(GroundProjection, DistortedPixelsAreUndistortedFirst) {
  const CameraIntrinsics ideal = vgaIntrinsics();
  const PinholeCamera& k = ideal.pinhole;
  const cv::Matx33d camera_matrix(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  struct Case {
    std::string model;
    std::vector<double> d;
  };
  for (const Case& test_case : {Case{"plumb_bob", {-0.28, 0.09, 0.001, -0.0005, 0.0}},
                                Case{"rational_polynomial", {-0.2, 0.05, 0.0, 0.0, 0.0, 0.1, 0.02, 0.0}},
                                Case{"equidistant", {-0.02, 0.01, -0.003, 0.0005}}}) {
    CameraIntrinsics distorted = ideal;
    distorted.distortion_model = test_case.model;
    distorted.distortion = test_case.d;
    ASSERT_EQ(validateIntrinsics(distorted), "");
    double worst = 0;
    for (double x = -0.6; x <= 0.6; x += 0.1) {
      for (double y = -0.45; y <= 0.45; y += 0.1) {
        const std::vector<cv::Point3d> point{{x, y, 1.0}};
        std::vector<cv::Point2d> raw;
        if (test_case.model == "equidistant") {
          cv::fisheye::projectPoints(point, raw, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix, cv::Mat(test_case.d));
        } else {
          cv::projectPoints(point, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix, cv::Mat(test_case.d), raw);
        }
        double u = 0, v = 0;
        ASSERT_TRUE(undistortPixel(distorted, raw[0].x, raw[0].y, &u, &v));
        worst = std::max(worst, std::hypot(u - (k.fx * x + k.cx), v - (k.fy * y + k.cy)));
      }
    }
    EXPECT_LT(worst, 0.01) << test_case.model;
    std::printf("[ distortion ] %s: worst undistortion error %.2g px\n", test_case.model.c_str(), worst);
  }
  CameraIntrinsics bad = ideal;
  bad.distortion_model = "plumb_bob";
  bad.distortion = {0.1, NAN, 0, 0, 0};
  EXPECT_NE(validateIntrinsics(bad), "");
  bad.distortion = {0.1, 0.2, 0.3};
  EXPECT_NE(validateIntrinsics(bad), "");
  bad.distortion_model = "fancy_lens";
  bad.distortion = {0.1, 0, 0, 0, 0};
  EXPECT_NE(validateIntrinsics(bad), "");
  bad.distortion = {0, 0, 0, 0, 0};  // all zero: no distortion whatever the model says
  EXPECT_EQ(validateIntrinsics(bad), "");
  bad.pinhole.fx = NAN;
  EXPECT_NE(validateIntrinsics(bad), "");
}

TEST(GroundProjection, ABoxFaceGivesItsContactPointWidthAndHeight) {
  const CameraIntrinsics c = vgaIntrinsics();
  const Eigen::Isometry3d pose = baseFromOptical(0, 20 * kDeg, 0, 0.45);
  for (double distance : {0.8, 1.5, 3.0}) {
    // A face 0.3 m wide and 0.4 m high standing across the optical axis at `distance`.
    const double half_width = 0.15, height = 0.4;
    const Eigen::Vector2d bottom_left = pixelOf(c.pinhole, pose, {distance, half_width, 0});
    const Eigen::Vector2d bottom_right = pixelOf(c.pinhole, pose, {distance, -half_width, 0});
    const Eigen::Vector2d top_left = pixelOf(c.pinhole, pose, {distance, half_width, height});
    // Pixels whose centres lie inside the face.
    const int left = static_cast<int>(std::ceil(bottom_left.x() - 0.5)), right = static_cast<int>(std::floor(bottom_right.x() - 0.5));
    const int bottom = static_cast<int>(std::floor(bottom_left.y() - 0.5)), top = static_cast<int>(std::ceil(top_left.y() - 0.5));
    GroundObstacle o;
    ASSERT_TRUE(projectBlobToGround(c, pose, outline(left, top, right, bottom), 100, &o));
    // The pixel grid moves each edge by up to 1 px: that much, at the face's depth.
    const double metres_per_px = (pose.inverse() * Eigen::Vector3d(distance, 0, 0)).z() / c.pinhole.fx * 1.5;
    EXPECT_NEAR(o.position.x(), distance, distance * distance / (0.45 * c.pinhole.fy) * 1.5);
    EXPECT_NEAR(o.position.y(), 0, metres_per_px);
    EXPECT_NEAR(o.width_m, 2 * half_width, metres_per_px);
    EXPECT_NEAR(o.height_m, height, 2 * metres_per_px);
    EXPECT_NEAR(o.range_m, o.position.head<2>().norm(), 1e-12);
    EXPECT_NEAR(o.bearing_rad, std::atan2(o.position.y(), o.position.x()), 1e-12);
    EXPECT_FALSE(o.clipped);
  }
  GroundObstacle o;
  ASSERT_TRUE(projectBlobToGround(c, pose, outline(300, 400, 340, 479), 100, &o));
  EXPECT_TRUE(o.clipped);
  std::string reason;
  EXPECT_FALSE(projectBlobToGround(c, pose, outline(300, 10, 340, 20), 100, &o, &reason));  // in the sky
  EXPECT_EQ(reason, "the point is at or above the horizon");
}

TEST(GroundProjection, ContactsRightAboveAnotherBlobMayBeHidden) {
  // A far box whose lower part hides behind a near one, a box beside it, a box above a gap.
  const std::vector<BlobOutline> blobs = {outline(100, 50, 140, 89), outline(90, 90, 160, 200),
                                          outline(200, 80, 230, 120), outline(100, 10, 140, 40)};
  EXPECT_TRUE(contactMayBeHidden(blobs, 0));
  EXPECT_FALSE(contactMayBeHidden(blobs, 1));
  EXPECT_FALSE(contactMayBeHidden(blobs, 2));
  EXPECT_FALSE(contactMayBeHidden(blobs, 3));  // 10 rows of ground between it and the next blob
  EXPECT_TRUE(contactMayBeHidden(blobs, 3, 12));
}

// Distance from a ground point to the boundary of a box's footprint (a rectangle).
double distanceToFootprintBoundary(const BoxTruth& box, const Eigen::Vector3d& p) {
  const Eigen::Vector2d d = p.head<2>() - box.position_m;
  const double c = std::cos(box.yaw_rad), s = std::sin(box.yaw_rad);
  const Eigen::Vector2d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());  // box axes: x depth, y width
  const double hx = 0.5 * box.depth_m, hy = 0.5 * box.width_m;
  const double ox = std::abs(local.x()) - hx, oy = std::abs(local.y()) - hy;
  if (ox > 0 || oy > 0) return std::hypot(std::max(ox, 0.0), std::max(oy, 0.0));  // outside
  return std::min(-ox, -oy);                                                       // inside
}

struct PlacementErrors {
  std::vector<double> relative;  // distance to the footprint's boundary / range
  std::vector<double> roll_deg, pitch_deg;
};

// Places every whole, unclipped box of 0.3-4 m over gait frames, with the true pose or with
// the pose from the detected horizon (yaw 0, the configured height).
PlacementErrors placeBoxes(bool pose_from_horizon) {
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_default.yaml")));
  CameraIntrinsics c;
  c.pinhole = simulator.camera();
  LandmarkDetector detector;
  LandmarkResult landmarks;
  PlacementErrors errors;
  for (int frame = 0; frame < 90; frame += 3) {  // 3 s of gait: every phase of roll, pitch, bob
    const SimFrame f = simulator.render(frame, frame / 30.0);
    Eigen::Isometry3d pose = baseFromOptical(f.pose.roll, f.pose.pitch, f.pose.yaw, f.pose.height_m);
    pose.translation() = Eigen::Vector3d(f.pose.x_m, f.pose.y_m, f.pose.height_m);
    if (pose_from_horizon) {
      detector.detectInImage(f.image, LandmarkOptions(), &landmarks);
      if (!landmarks.horizon.found) continue;
      double roll = 0, pitch = 0;
      attitudeFromHorizon(c.pinhole, landmarks.horizon.line, &roll, &pitch);
      errors.roll_deg.push_back(std::abs(roll - f.pose.roll) / kDeg);
      errors.pitch_deg.push_back(std::abs(pitch - f.pose.pitch) / kDeg);
      pose = baseFromOptical(roll, pitch, 0, simulator.config().camera_height_m);
    }
    for (const BoxTruth& box : f.boxes) {
      if (box.area < 200 || box.pieces != 1 || box.touches_other_box) continue;
      GroundObstacle o;
      if (!projectBlobToGround(c, pose, truthOutline(f, box), 100, &o)) continue;
      if (o.clipped || o.range_m < 0.3 || o.range_m > 4) continue;
      errors.relative.push_back(distanceToFootprintBoundary(box, o.position) / o.range_m);
    }
  }
  return errors;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

TEST(GroundProjection, BoxesLandOnTheirFootprintsWithTheTruePose) {
  const PlacementErrors e = placeBoxes(false);
  ASSERT_GE(e.relative.size(), 50u);
  const double worst = *std::max_element(e.relative.begin(), e.relative.end());
  std::printf("[ ground, tf pose ] %zu placements: contact point to footprint edge median %.2f%%, worst %.2f%% of range\n",
              e.relative.size(), 100 * median(e.relative), 100 * worst);
  EXPECT_LT(worst, 0.03);
}

TEST(GroundProjection, BoxesLandOnTheirFootprintsWithThePoseFromTheHorizon) {
  const PlacementErrors e = placeBoxes(true);
  ASSERT_GE(e.relative.size(), 50u);
  ASSERT_GE(e.roll_deg.size(), 28u);
  const double worst = *std::max_element(e.relative.begin(), e.relative.end());
  std::printf("[ ground, horizon pose ] %zu placements: median %.2f%%, worst %.2f%% of range; "
              "roll error median %.3f deg, pitch %.3f deg\n",
              e.relative.size(), 100 * median(e.relative), 100 * worst, median(e.roll_deg), median(e.pitch_deg));
  EXPECT_LT(median(e.roll_deg), 0.5);
  EXPECT_LT(median(e.pitch_deg), 0.5);
  EXPECT_LT(worst, 0.05);
}

// The camera's sway in the attitude tests' gait: roll 3 deg at 1 Hz, pitch 20 deg +- 2 deg at 2 Hz.
double gaitRoll(double t) { return 3 * kDeg * std::sin(2 * M_PI * t); }
double gaitPitch(double t) { return 20 * kDeg + 2 * kDeg * std::sin(4 * M_PI * t); }

// The gait's horizon at t (s), as the landmark node would send it with `confidence`.
AttitudeTimeline::Update addGaitHorizon(AttitudeTimeline* timeline, double t, double confidence) {
  return timeline->addHorizon(true, gaitRoll(t), gaitPitch(t), confidence, t);
}

TEST(AttitudeFilter, FollowsAGaitWithoutLagAndIgnoresGlitches) {
  AttitudeFilterOptions options;
  options.smoothing = 0.1;
  AttitudeFilter filter(options);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.05 * kDeg);
  double worst_after_settling = 0;
  int glitches_rejected = 0;
  for (int i = 0; i < 300; ++i) {
    const double t = i / 30.0;
    const double roll = gaitRoll(t), pitch = gaitPitch(t);
    if (i % 37 == 20) {  // a wrong horizon (e.g. a box's top edge), 15 deg off
      glitches_rejected += filter.update(true, roll + 15 * kDeg, pitch, 0.9, t) == AttitudeFilter::Outcome::kJump;
      continue;
    }
    ASSERT_EQ(filter.update(true, roll + noise(rng), pitch + noise(rng), 0.9, t), AttitudeFilter::Outcome::kAccepted);
    if (t > 1.0) {
      worst_after_settling = std::max({worst_after_settling, std::abs(filter.roll() - roll), std::abs(filter.pitch() - pitch)});
    }
  }
  EXPECT_EQ(glitches_rejected, 8);
  EXPECT_LT(worst_after_settling, 0.25 * kDeg);
  std::printf("[ attitude filter ] gait (roll 3 deg at 1 Hz, pitch 2 deg at 2 Hz), smoothing 0.1: worst error %.3f deg after 1 s\n",
              worst_after_settling / kDeg);
}

TEST(AttitudeFilter, GatesHoldsAndRestarts) {
  AttitudeFilterOptions options;
  options.smoothing = 0.0;
  options.max_rejected = 3;
  options.max_hold_s = 0.5;
  AttitudeFilter filter(options);
  EXPECT_FALSE(filter.valid(0.0));
  EXPECT_EQ(filter.update(true, 0.1, 0.3, 0.2, 0.0), AttitudeFilter::Outcome::kLowConfidence);
  EXPECT_EQ(filter.update(false, 0.1, 0.3, 1.0, 0.0), AttitudeFilter::Outcome::kNoHorizon);
  EXPECT_EQ(filter.update(true, NAN, 0.3, 1.0, 0.0), AttitudeFilter::Outcome::kNoHorizon);
  EXPECT_EQ(filter.update(true, 0.1, 0.3, 1.0, 0.0), AttitudeFilter::Outcome::kAccepted);
  EXPECT_DOUBLE_EQ(filter.roll(), 0.1);
  EXPECT_DOUBLE_EQ(filter.pitch(), 0.3);
  EXPECT_EQ(filter.update(true, 0.2, 0.3, 1.0, 0.0), AttitudeFilter::Outcome::kNoHorizon);  // same stamp
  // The camera really tilted: two jumps are refused, the third is believed.
  EXPECT_EQ(filter.update(true, 0.6, 0.3, 1.0, 0.1), AttitudeFilter::Outcome::kJump);
  EXPECT_EQ(filter.update(true, 0.6, 0.3, 1.0, 0.2), AttitudeFilter::Outcome::kJump);
  EXPECT_EQ(filter.update(true, 0.6, 0.3, 1.0, 0.3), AttitudeFilter::Outcome::kAccepted);
  EXPECT_DOUBLE_EQ(filter.roll(), 0.6);
  EXPECT_TRUE(filter.valid(0.7));
  EXPECT_FALSE(filter.valid(0.9));  // held too long
  // After the hold expires any horizon restarts the filter.
  EXPECT_EQ(filter.update(true, -0.4, 0.2, 1.0, 1.0), AttitudeFilter::Outcome::kAccepted);
  EXPECT_DOUBLE_EQ(filter.roll(), -0.4);
  options.smoothing = 1.0;
  EXPECT_NE(validateAttitudeFilterOptions(options), "");
  options.smoothing = NAN;
  EXPECT_NE(validateAttitudeFilterOptions(options), "");
}

// A starved landmark node sends horizons far apart: over such a gap the filter's rate says
// little (the gait turns within it), so its gate holds each horizon against the last accepted
// attitude, not against the rate carried across the gap; before, horizons 0.3 s apart in the gait
// were taken for glitches (the rate carried over 0.3 s overshoots by more than max_jump_deg).
// A glitch is still one, however long the gap.
TEST(AttitudeFilter, HorizonsFarApartAreNotTakenForGlitches) {
  for (double gap_s : {0.2, 0.3, 0.5}) {
    AttitudeFilterOptions options;  // max_jump_deg 10, max_gap_s 0.15
    options.smoothing = 0.0;
    AttitudeFilter filter(options);
    for (int i = 0; i < 30; ++i) ASSERT_EQ(filter.update(true, gaitRoll(i / 30.0), gaitPitch(i / 30.0), 0.9, i / 30.0), AttitudeFilter::Outcome::kAccepted);
    int rejected = 0, glitches_rejected = 0, glitches = 0;
    for (double t = 1.0; t < 4.0; t += gap_s) {
      if (static_cast<int>(std::lround((t - 1.0) / gap_s)) % 4 == 3) {  // a box's top edge, 15 deg off
        ++glitches;
        glitches_rejected += filter.update(true, gaitRoll(t) + 15 * kDeg, gaitPitch(t), 0.9, t) == AttitudeFilter::Outcome::kJump;
        continue;
      }
      rejected += filter.update(true, gaitRoll(t), gaitPitch(t), 0.9, t) != AttitudeFilter::Outcome::kAccepted;
    }
    std::printf("[ attitude filter ] horizons %.1f s apart in the gait: %d true ones rejected, %d of %d glitches rejected\n",
                gap_s, rejected, glitches_rejected, glitches);
    EXPECT_EQ(rejected, 0) << gap_s;
    EXPECT_EQ(glitches_rejected, glitches) << gap_s;
  }
}

// The gait's sway between horizons 100 ms apart (the landmark node skipped two frames): the
// timeline follows it, where a linear interpolation of the same horizons is off by 0.4 deg.
TEST(AttitudeTimeline, FollowsTheGaitAcrossSkippedHorizons) {
  AttitudeTimeline timeline;
  // Horizons at 30 Hz for 2 s, then two frames of every three skipped.
  std::vector<double> horizon_stamps;
  for (int i = 0; i < 60; ++i) horizon_stamps.push_back(i / 30.0);
  for (int i = 60; i <= 123; i += 3) horizon_stamps.push_back(i / 30.0);
  for (double t : horizon_stamps) {
    ASSERT_TRUE(addGaitHorizon(&timeline, t, 0.9).valid);
  }
  double worst = 0, worst_linear = 0;
  for (int i = 61; i < 120; ++i) {
    if (i % 3 == 0) continue;
    const double t = i / 30.0;
    double roll = 0, pitch = 0;
    ASSERT_EQ(timeline.attitudeAt(t, &roll, &pitch), AttitudeTimeline::Lookup::kFound);
    worst = std::max({worst, std::abs(roll - gaitRoll(t)), std::abs(pitch - gaitPitch(t))});
    const double t0 = (i / 3) * 3 / 30.0, t1 = t0 + 0.1, f = (t - t0) / 0.1;
    worst_linear = std::max(worst_linear, std::abs(gaitPitch(t0) + f * (gaitPitch(t1) - gaitPitch(t0)) - gaitPitch(t)));
  }
  EXPECT_LT(worst, 0.15 * kDeg);
  EXPECT_GT(worst_linear, 0.3 * kDeg);
  double roll = 0, pitch = 0;
  EXPECT_EQ(timeline.attitudeAt(4.2, &roll, &pitch), AttitudeTimeline::Lookup::kNotYet);  // after the newest
  EXPECT_EQ(timeline.attitudeAt(4.05, &roll, &pitch), AttitudeTimeline::Lookup::kNotYet);  // the end's rate unknown yet
  EXPECT_EQ(timeline.attitudeAt(-0.5, &roll, &pitch), AttitudeTimeline::Lookup::kLost);  // before the oldest
  std::printf("[ attitude timeline ] 100-ms gaps in the horizons: worst error %.3f deg (linear interpolation %.3f deg)\n",
              worst / kDeg, worst_linear / kDeg);
}

// Horizons every `gap_s` through the same gait: the worst error of the attitude interpolated
// between them (rad), or -1 when no image between them gets one.
double worstErrorBetweenHorizons(double gap_s, const AttitudeFilterOptions& options) {
  AttitudeTimeline timeline(options);
  for (int i = 0; i < 30; ++i) addGaitHorizon(&timeline, i / 30.0, 0.9);
  for (double t = 1.0; t <= 2.5 + gap_s; t += gap_s) addGaitHorizon(&timeline, t, 0.9);
  double worst = -1;
  for (double t = 1.0 + 2 * gap_s + 1.0 / 60; t < 2.5; t += 1.0 / 30) {  // between frames, not at a horizon
    double roll = 0, pitch = 0;
    if (timeline.attitudeAt(t, &roll, &pitch) != AttitudeTimeline::Lookup::kFound) continue;
    worst = std::max({worst, std::abs(roll - gaitRoll(t)), std::abs(pitch - gaitPitch(t))});
  }
  return worst;
}

// A loaded machine's landmark node sends horizons far apart: across a larger share of the sway
// the interpolated attitude is wrong by degrees (an obstacle at 2 m by tens of percent), so
// images in gaps longer than max_gap_s get none.
TEST(AttitudeTimeline, NoAttitudeAcrossGapsLongerThanMaxGap) {
  AttitudeFilterOptions options;  // max_gap_s 0.15 by default
  options.smoothing = 0.0;
  for (double gap_s : {0.1, 0.15, 0.2, 0.3, 0.5}) {
    AttitudeFilterOptions wide = options;
    wide.max_gap_s = 1.0;
    wide.max_jump_deg = 90;  // the gate carries the rate across gaps up to max_gap_s: here all are taken
    std::printf("[ attitude timeline ] horizons %.2f s apart in the gait: worst error between them %.2f deg\n", gap_s,
                worstErrorBetweenHorizons(gap_s, wide) / kDeg);
  }
  EXPECT_LT(worstErrorBetweenHorizons(0.1, options), 0.15 * kDeg);
  const double at_max_gap = worstErrorBetweenHorizons(0.149, options);
  EXPECT_GE(at_max_gap, 0.0);
  EXPECT_LT(at_max_gap, 0.5 * kDeg);
  EXPECT_EQ(worstErrorBetweenHorizons(0.2, options), -1.0);  // every image in a gap: none
  options.max_gap_s = 0.5;
  options.max_jump_deg = 90;
  EXPECT_GT(worstErrorBetweenHorizons(0.45, options), 1.0 * kDeg);  // what a longer gap costs
  options.max_gap_s = NAN;
  EXPECT_NE(validateAttitudeFilterOptions(options), "");
}

// Runs of rejected horizons (below horizon_min_confidence: a box's top edge, a frame with no sky)
// in the gait at 30 Hz: the images there get the attitude interpolated between the accepted
// horizons on both sides, not the filter's extrapolation past the last one (what a rejected
// horizon reports, with confidence 0), which is off by far more; inside a run spanning more than
// max_gap_s they get none.
TEST(AttitudeTimeline, RejectedHorizonsAreBridgedNotExtrapolated) {
  AttitudeFilterOptions options;  // horizon_min_confidence 0.5, max_gap_s 0.15
  options.smoothing = 0.0;
  AttitudeTimeline timeline(options);
  std::map<int, double> worst_extrapolated, worst_bridged;  // by run length (rad)
  int i = 0;
  for (; i < 30; ++i) ASSERT_TRUE(addGaitHorizon(&timeline, i / 30.0, 0.9).recorded);
  for (int cycle = 0; cycle < 3; ++cycle) {
    for (int run : {1, 2, 3, 4, 6}) {
      std::vector<double> stamps;
      for (int k = 0; k < run; ++k, ++i) {
        const double t = i / 30.0;
        const AttitudeTimeline::Update update = addGaitHorizon(&timeline, t, 0.1);
        ASSERT_TRUE(update.valid);
        ASSERT_FALSE(update.recorded);
        EXPECT_EQ(update.attitude.confidence, 0.0);
        const double error = std::max(std::abs(update.attitude.roll - gaitRoll(t)), std::abs(update.attitude.pitch - gaitPitch(t)));
        worst_extrapolated[run] = std::max(worst_extrapolated[run], error);
        stamps.push_back(t);
      }
      for (int k = 0; k < 4; ++k, ++i) addGaitHorizon(&timeline, i / 30.0, 0.9);
      for (double t : stamps) {  // the run's images, once the accepted horizons after it came
        double roll = 0, pitch = 0;
        const AttitudeTimeline::Lookup lookup = timeline.attitudeAt(t, &roll, &pitch);
        if ((run + 1) / 30.0 > options.max_gap_s) {
          EXPECT_EQ(lookup, AttitudeTimeline::Lookup::kLost) << "t " << t;
          continue;
        }
        ASSERT_EQ(lookup, AttitudeTimeline::Lookup::kFound) << "t " << t;
        worst_bridged[run] = std::max({worst_bridged[run], std::abs(roll - gaitRoll(t)), std::abs(pitch - gaitPitch(t))});
      }
    }
  }
  for (const auto& [run, extrapolated] : worst_extrapolated) {
    const auto bridged = worst_bridged.find(run);
    std::printf("[ attitude timeline ] %d rejected horizons in a row: worst error extrapolated %.2f deg, bridged %.2f deg%s\n",
                run, extrapolated / kDeg, bridged == worst_bridged.end() ? 0.0 : bridged->second / kDeg,
                bridged == worst_bridged.end() ? " (none: a gap over max_gap_s)" : "");
  }
  for (const auto& [run, bridged] : worst_bridged) {
    EXPECT_LT(bridged, 0.5 * kDeg) << run;
    EXPECT_LT(bridged, 0.5 * worst_extrapolated[run]) << run;
  }
  EXPECT_EQ(worst_bridged.size(), 3u);  // runs of 1, 2 and 3 frames: within max_gap_s
}

TEST(AttitudeTimeline, LongGapsAndTimeGoingBackwards) {
  AttitudeFilterOptions options;
  options.max_hold_s = 0.5;
  AttitudeTimeline timeline(options);
  EXPECT_FALSE(timeline.addHorizon(true, 0.1, 0.3, 0.2, 0.0).valid);  // low confidence: no attitude yet
  EXPECT_TRUE(timeline.addHorizon(true, 0.1, 0.3, 0.9, 1.0).valid);
  EXPECT_TRUE(timeline.addHorizon(true, 0.1, 0.3, 0.9, 2.0).valid);  // after a gap: the filter restarts
  double roll = 0, pitch = 0;
  EXPECT_EQ(timeline.attitudeAt(1.5, &roll, &pitch), AttitudeTimeline::Lookup::kLost);  // no attitude inside the gap
  EXPECT_EQ(timeline.attitudeAt(2.0, &roll, &pitch), AttitudeTimeline::Lookup::kFound);
  EXPECT_DOUBLE_EQ(roll, 0.1);
  // A rejected horizon still reports the attitude moved on by the filter, with confidence 0,
  // but does not record it for the images.
  const AttitudeTimeline::Update low = timeline.addHorizon(true, 0.1, 0.3, 0.1, 2.1);
  EXPECT_TRUE(low.valid);
  EXPECT_FALSE(low.recorded);
  EXPECT_EQ(low.attitude.confidence, 0.0);
  EXPECT_EQ(timeline.attitudeAt(2.1, &roll, &pitch), AttitudeTimeline::Lookup::kNotYet);
  // A looped bag: time goes back, everything starts over.
  const AttitudeTimeline::Update looped = timeline.addHorizon(true, -0.2, 0.1, 0.9, 0.5);
  EXPECT_TRUE(looped.restarted);
  EXPECT_TRUE(looped.valid);
  EXPECT_EQ(timeline.attitudeAt(2.0, &roll, &pitch), AttitudeTimeline::Lookup::kNotYet);
}

}  // namespace
}  // namespace rle_vision
