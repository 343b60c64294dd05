// The field boundary on the ground, with known answers: an image row seen by a pitched camera is
// a straight line on the ground (range d / cos(bearing) per bearing), and the simulated hall's
// exact boundary (and the one the field stage finds) lands on the carpet's border.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rle_vision/field/field_detector.h"
#include "rle_vision/ground/field_edge.h"
#include "rle_vision/ground/ground_projection.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;

TEST(FieldEdge, AnImageRowIsAStraightEdgeOnTheGround) {
  CameraIntrinsics c;
  c.pinhole = PinholeCamera::fromHorizontalFov(640, 480, 70 * kDeg);
  const double pitch = 20 * kDeg, height = 0.5;
  const Eigen::Isometry3d pose = baseFromOptical(0, pitch, 0, height);
  const double row = 300;  // below the image centre: farther down than the optical axis
  const double distance = height / std::tan(pitch + std::atan((row - c.pinhole.cy) / c.pinhole.fy));
  // The field's top pixels in row 300.5 have their upper side, the edge, at row 300.
  const FieldEdgeOnGround edge = projectFieldEdge(c, pose, {{0, row + 0.5}, {639, row + 0.5}}, 10.0, 1 * kDeg);
  ASSERT_GE(edge.points.size(), 600u);
  for (const Eigen::Vector3d& p : edge.points) EXPECT_NEAR(p.x(), distance, 1e-6);
  EXPECT_GT(edge.points.front().y(), 0);  // the image's left is the robot's left
  ASSERT_GE(edge.ranges_m.size(), 60u);   // 70 degrees of view in 1 degree bins
  EXPECT_NEAR(edge.bearing_min_rad / kDeg, std::round(edge.bearing_min_rad / kDeg), 1e-9);  // bins on whole degrees
  for (size_t i = 0; i < edge.ranges_m.size(); ++i) {
    const double bearing = edge.bearing_min_rad + i * edge.bearing_step_rad;
    ASSERT_TRUE(std::isfinite(edge.ranges_m[i])) << "bin " << i;
    // The nearest point in the bin: within half a bin of its centre.
    EXPECT_NEAR(edge.ranges_m[i], distance / std::cos(bearing), distance * 0.02) << "bin " << i;
  }
  // Above the horizon, beyond the range limit, empty, non-finite: nothing, never infinity.
  EXPECT_TRUE(projectFieldEdge(c, pose, {{0, 10}, {639, 10}}, 10.0, 1 * kDeg).points.empty());
  EXPECT_TRUE(projectFieldEdge(c, pose, {{0, row + 0.5}, {639, row + 0.5}}, 0.5 * distance, 1 * kDeg).ranges_m.empty());
  EXPECT_TRUE(projectFieldEdge(c, pose, {}, 10.0, 1 * kDeg).points.empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(projectFieldEdge(c, pose, {{0, nan}, {639, nan}}, 10.0, 1 * kDeg).points.empty());
  EXPECT_TRUE(projectFieldEdge(c, pose, {{nan, row + 0.5}, {639, row + 0.5}}, 10.0, 1 * kDeg).points.size() <= 1);
  EXPECT_TRUE(projectFieldEdge(c, pose, {{-1e12, row + 0.5}, {1e12, row + 0.5}}, 10.0, 1 * kDeg).ranges_m.empty());
  // Looking backwards (yaw 180 degrees): the bearings straddle +-pi and the bins stay contiguous.
  const FieldEdgeOnGround back =
      projectFieldEdge(c, baseFromOptical(0, pitch, M_PI, height), {{0, row + 0.5}, {639, row + 0.5}}, 10.0, 1 * kDeg);
  ASSERT_EQ(back.ranges_m.size(), edge.ranges_m.size());  // as many bins as looking forwards, not 360
  const double middle = back.bearing_min_rad + 0.5 * (back.ranges_m.size() - 1) * back.bearing_step_rad;
  EXPECT_NEAR(std::remainder(middle - M_PI, 2 * M_PI), 0.0, 2 * kDeg);
  EXPECT_TRUE(projectFieldEdge(c, pose, {{0, row}, {639, row}}, 10.0, 0.0).points.empty());
}

// Distance of a ground point to the border of the field rectangle.
double toBorder(const SceneConfig& s, const Eigen::Vector3d& p) {
  const double dx = std::min(std::abs(p.x() - s.field_x_min_m), std::abs(p.x() - s.field_x_max_m));
  const double dy = std::min(std::abs(p.y() - s.field_y_min_m), std::abs(p.y() - s.field_y_max_m));
  return std::min(dx, dy);
}

TEST(FieldEdge, TheSimulatedHallsBoundaryLandsOnTheCarpetsBorder) {
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_field.yaml")));
  CameraIntrinsics c;
  c.pinhole = simulator.camera();
  FieldDetector detector;
  std::vector<double> exact, found;
  for (int frame = 0; frame < 60; frame += 3) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    Eigen::Isometry3d pose = baseFromOptical(f.pose.roll, f.pose.pitch, f.pose.yaw, f.pose.height_m);
    pose.translation() = Eigen::Vector3d(f.pose.x_m, f.pose.y_m, f.pose.height_m);
    // The exact boundary: the top field row's centre sees the field, the row above's does not;
    // the edge lies between them (where projectFieldEdge puts it: the top pixel's upper side).
    std::vector<Eigen::Vector2d> truth;
    for (int u = 0; u < f.image.cols; u += 8) {
      if (!std::isnan(f.field_top[u])) truth.emplace_back(u, f.field_top[u]);
    }
    for (const Eigen::Vector3d& p : projectFieldEdge(c, pose, truth, 20.0, 1 * kDeg, 8.0).points) {
      exact.push_back(toBorder(simulator.config(), p) / p.head<2>().norm());
    }
    FieldResult result;
    detector.detect(f.image, &result);
    ASSERT_TRUE(result.boundary.found) << "frame " << frame;
    std::vector<Eigen::Vector2d> polyline;
    for (const cv::Point2f& q : result.boundary.polyline) polyline.emplace_back(q.x, q.y);
    for (const Eigen::Vector3d& p : projectFieldEdge(c, pose, polyline, 20.0, 1 * kDeg, 8.0).points) {
      found.push_back(toBorder(simulator.config(), p) / p.head<2>().norm());
    }
  }
  ASSERT_GE(exact.size(), 500u);
  ASSERT_GE(found.size(), 500u);
  std::sort(exact.begin(), exact.end());
  std::sort(found.begin(), found.end());
  std::printf("[ field edge ] on the ground, distance to the carpet's border / range: exact boundary median %.2f%%, "
              "worst %.2f%%; found boundary median %.2f%%, 95%% %.2f%%\n",
              100 * exact[exact.size() / 2], 100 * exact.back(), 100 * found[found.size() / 2],
              100 * found[found.size() * 95 / 100]);
  EXPECT_LT(exact[exact.size() / 2], 0.01);
  EXPECT_LT(exact.back(), 0.02);
  EXPECT_LT(found[found.size() / 2], 0.02);
  EXPECT_LT(found[found.size() * 95 / 100], 0.05);
}

}  // namespace
}  // namespace rle_vision
