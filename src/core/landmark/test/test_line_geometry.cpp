// The paper's (theta, intercept) line parameters and the horizon <-> attitude geometry.
#include <random>

#include <gtest/gtest.h>

#include "rle_vision/ground/camera_model.h"
#include "eval/horizon_metrics.h"
#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;

TEST(LineGeometry, AnglesAreNormalisedToMinusNinetyExclusiveToNinetyInclusive) {
  EXPECT_NEAR(normalizeLineAngle(M_PI / 2), M_PI / 2, 1e-12);
  EXPECT_NEAR(normalizeLineAngle(-M_PI / 2), M_PI / 2, 1e-12);
  EXPECT_NEAR(normalizeLineAngle(M_PI), 0, 1e-12);
  EXPECT_NEAR(normalizeLineAngle(3 * M_PI / 4), -M_PI / 4, 1e-12);
  EXPECT_NEAR(lineAngleDifference(89 * kDeg, -89 * kDeg), 2 * kDeg, 1e-12);
}

TEST(LineGeometry, HorizontalAndVerticalLines) {
  const ImageLine h = lineThroughPoints(10, 40, 300, 40);
  EXPECT_NEAR(h.theta, 0, 1e-12);
  EXPECT_NEAR(h.intercept, 40, 1e-9);  // y-intercept
  const ImageLine v = lineThroughPoints(25, 5, 25, 300);
  EXPECT_NEAR(v.theta, M_PI / 2, 1e-12);
  EXPECT_NEAR(v.intercept, 25, 1e-9);  // x-intercept
  const ImageLine v_up = lineThroughPoints(25, 300, 25, 5);  // direction does not matter
  EXPECT_NEAR(v_up.theta, M_PI / 2, 1e-12);
}

TEST(LineGeometry, InterceptsAreEqualAtMinus45AndOppositeAtPlus45) {
  // theta = -45 deg: y = c - x, x-intercept c: continuous across the switch.
  const ImageLine minus = lineThroughPoints(0, 100, 100, 0);
  EXPECT_NEAR(minus.theta, -M_PI / 4, 1e-12);
  EXPECT_NEAR(minus.intercept, 100, 1e-9);
  EXPECT_FALSE(usesYIntercept(minus.theta));
  const ImageLine just_above = lineThroughPointWithAngle(50, 50, -M_PI / 4 + 1e-9);
  EXPECT_TRUE(usesYIntercept(just_above.theta));
  EXPECT_NEAR(just_above.intercept, 100, 1e-6);
  // theta = +45 deg: y = x - 30: y-intercept -30, x-intercept +30.
  const ImageLine plus = lineThroughPoints(30, 0, 130, 100);
  EXPECT_NEAR(plus.theta, M_PI / 4, 1e-12);
  EXPECT_TRUE(usesYIntercept(plus.theta));
  EXPECT_NEAR(plus.intercept, -30, 1e-9);
  const ImageLine just_past = lineThroughPointWithAngle(30, 0, M_PI / 4 + 1e-9);
  EXPECT_NEAR(just_past.intercept, 30, 1e-6);
}

TEST(LineGeometry, InterceptsStayInThePapersRange) {
  // alpha = -max(H, W), beta = H + W for every line through the image.
  const int width = 640, height = 480;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> x(0, width - 1), y(0, height - 1), angle(-M_PI, M_PI);
  for (int i = 0; i < 100000; ++i) {
    const ImageLine line = lineThroughPointWithAngle(x(rng), y(rng), angle(rng));
    ASSERT_GE(line.intercept, -std::max(width, height) - 1e-6);
    ASSERT_LE(line.intercept, width + height + 1e-6);
  }
}

TEST(LineGeometry, HomogeneousRoundTripAndDistance) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> coord(-100, 700), angle(-M_PI, M_PI);
  for (int i = 0; i < 1000; ++i) {
    const ImageLine line = lineThroughPointWithAngle(coord(rng), coord(rng), angle(rng));
    double a, b, c;
    homogeneousFromLine(line, &a, &b, &c);
    const double k = 3.7;
    const ImageLine back = lineFromHomogeneous(k * a, k * b, k * c);
    EXPECT_NEAR(lineAngleDifference(back.theta, line.theta), 0, 1e-9);
    EXPECT_NEAR(back.intercept, line.intercept, 1e-6);
    double px, py;
    pointOnLine(line, &px, &py);
    EXPECT_NEAR(signedDistance(line, px - 5 * std::sin(line.theta), py + 5 * std::cos(line.theta)), 5, 1e-9);
  }
}

TEST(LineGeometry, ClipsToTheImage) {
  double x1, y1, x2, y2;
  ASSERT_TRUE(clipLineToImage(lineThroughPoints(0, 10, 1, 10), 640, 480, &x1, &y1, &x2, &y2));
  EXPECT_NEAR(x1, -0.5, 1e-9);
  EXPECT_NEAR(x2, 639.5, 1e-9);
  EXPECT_NEAR(y1, 10, 1e-9);
  EXPECT_FALSE(clipLineToImage(lineThroughPoints(0, -10, 1, -10), 640, 480, &x1, &y1, &x2, &y2));
}

TEST(CameraModel, HorizonRoundTripsToRollAndPitch) {
  const PinholeCamera camera = PinholeCamera::fromHorizontalFov(640, 480, 70 * kDeg);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> roll(-30 * kDeg, 30 * kDeg), pitch(-25 * kDeg, 40 * kDeg),
      yaw(-M_PI, M_PI);
  for (int i = 0; i < 200; ++i) {
    const double r = roll(rng), p = pitch(rng);
    const Eigen::Matrix3d base_from_optical = opticalToBaseRotation(r, p, yaw(rng));
    double a, b, c;
    ASSERT_TRUE(horizonFromUp(camera, base_from_optical.transpose() * Eigen::Vector3d::UnitZ(), &a, &b, &c));
    const ImageLine horizon = lineFromHomogeneous(a, b, c);
    EXPECT_NEAR(normalizeLineAngle(horizon.theta + r), 0, 1e-9) << "theta = -roll when fx = fy";
    double r_est, p_est;
    attitudeFromHorizon(camera, horizon, &r_est, &p_est);
    EXPECT_NEAR(r_est, r, 1e-9);
    EXPECT_NEAR(p_est, p, 1e-9);
  }
}

TEST(CameraModel, LevelCameraSeesTheHorizonThroughThePrincipalPoint) {
  const PinholeCamera camera = PinholeCamera::fromHorizontalFov(640, 480, 70 * kDeg);
  double a, b, c;
  ASSERT_TRUE(horizonFromUp(camera, opticalToBaseRotation(0, 0, 0).transpose() * Eigen::Vector3d::UnitZ(), &a, &b, &c));
  const ImageLine level = lineFromHomogeneous(a, b, c);
  EXPECT_NEAR(level.theta, 0, 1e-12);
  EXPECT_NEAR(level.intercept, camera.cy, 1e-9);
  // Pitching 10 deg nose down moves it up by f * tan(10 deg).
  ASSERT_TRUE(horizonFromUp(camera, opticalToBaseRotation(0, 10 * kDeg, 0).transpose() * Eigen::Vector3d::UnitZ(), &a, &b, &c));
  EXPECT_NEAR(lineFromHomogeneous(a, b, c).intercept, camera.cy - camera.fy * std::tan(10 * kDeg), 1e-9);
  // Looking straight down there is no horizon.
  EXPECT_FALSE(horizonFromUp(camera, opticalToBaseRotation(0, M_PI / 2, 0).transpose() * Eigen::Vector3d::UnitZ(), &a, &b, &c));
}

}  // namespace
}  // namespace rle_vision

// make eval's horizon criterion (src/tools/eval/horizon_metrics.h) on known lines.
namespace rle_vision {
namespace {

TEST(HorizonMetrics, HesseDistanceAndThePassCriterion) {
  const int w = 480, h = 480;
  eval::HorizonLabel label;
  label.slope = 0;
  label.offset = 0.5;  // y = 240, through the image centre (239.5) half a pixel below
  const ImageLine truth = label.line(h);
  EXPECT_NEAR(eval::hesseDistanceFromCentre(truth, w, h), 0.5, 1e-9);
  // The same line described the other way round compares equal.
  EXPECT_NEAR(eval::hesseDistanceFromCentre(lineThroughPoints(400, 240, 10, 240), w, h), 0.5, 1e-9);
  // 20 px lower and 3 deg tilted about the centre: passes (< 24 px, < 5 deg).
  const double t = 3 * M_PI / 180;
  const ImageLine tilted = lineThroughPointWithAngle(239.5, 259.5, t);
  const eval::HorizonError e = eval::horizonError(tilted, truth, w, h);
  EXPECT_NEAR(e.angle_deg, 3.0, 1e-9);
  EXPECT_NEAR(e.distance_px, 20 * std::cos(t) - 0.5, 1e-6);
  EXPECT_TRUE(eval::passes(e, h));
  EXPECT_FALSE(eval::passes(eval::horizonError(lineThroughPointWithAngle(239.5, 265.5, 0), truth, w, h), h));
  EXPECT_FALSE(eval::passes(eval::horizonError(lineThroughPointWithAngle(239.5, 239.5, 6 * M_PI / 180), truth, w, h), h));
  // A segment on it: long enough, parallel within 2 deg, its centre within 3% H.
  EXPECT_TRUE(eval::segmentOnHorizon(100, 245, 200, 247, truth, h));
  EXPECT_FALSE(eval::segmentOnHorizon(100, 245, 130, 245, truth, h));  // 30 px: too short
  EXPECT_FALSE(eval::segmentOnHorizon(100, 260, 200, 260, truth, h));  // 20 px off
}

}  // namespace
}  // namespace rle_vision
