// The scene simulator's ground truth is exact: horizon, masks, pose, lighting, noise.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"
#include "rle_vision/sim/sensor_noise.h"
#include "testing/test_helpers.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {
namespace {

SceneConfig defaultScene() { return loadSceneConfig(test::sourcePath("config/scene_default.yaml")); }

TEST(SceneSimulator, SkyPixelsLieExactlyAboveTheHorizon) {
  SceneConfig scene = defaultScene();
  scene.boxes.clear();
  scene.camera_roll_deg = 12;
  const SceneSimulator simulator(scene);
  for (int frame = 0; frame < 10; ++frame) {
    const SimFrame f = simulator.render(frame, frame * 0.13);
    ASSERT_TRUE(f.horizon_visible);
    EXPECT_NEAR(normalizeLineAngle(f.horizon.theta + f.pose.roll), 0, 1e-9);
    for (int y = 0; y < f.labels.rows; ++y) {
      for (int x = 0; x < f.labels.cols; ++x) {
        // The sky side is the negative side of the line's normal (-sin, cos) while |roll| < 90.
        const double d = signedDistance(f.horizon, x, y);
        const uint8_t label = f.labels.at<uint8_t>(y, x);
        if (d < -1e-6) {
          ASSERT_EQ(label, SceneSimulator::kSkyLabel) << x << "," << y;
        } else if (d > 1e-6) {
          ASSERT_EQ(label, SceneSimulator::kGroundLabel) << x << "," << y;
        }
      }
    }
  }
}

TEST(SceneSimulator, TruthMatchesTheLabelImage) {
  const SceneSimulator simulator(defaultScene());
  const SimFrame f = simulator.render(3, 0.1);
  ASSERT_EQ(f.boxes.size(), 10u);
  for (const BoxTruth& box : f.boxes) {
    const cv::Mat mask = f.labels == box.label;
    EXPECT_EQ(static_cast<uint32_t>(cv::countNonZero(mask)), box.area) << box.name;
    if (box.area == 0) continue;
    const cv::Moments m = cv::moments(mask, true);
    EXPECT_NEAR(m.m10 / m.m00, box.cx, 1e-9);
    EXPECT_NEAR(m.m01 / m.m00, box.cy, 1e-9);
    const cv::Rect bbox = cv::boundingRect(mask);
    EXPECT_EQ(bbox.x, box.left);
    EXPECT_EQ(bbox.y, box.top);
    EXPECT_EQ(bbox.x + bbox.width - 1, box.right);
    EXPECT_EQ(bbox.y + bbox.height - 1, box.bottom);
  }
}

TEST(SceneSimulator, PiecesAndSameClassContactAgreeWithClassComponents) {
  SceneConfig scene = defaultScene();
  // Crowd the scene: boxes of one colour overlap and occlude each other.
  for (size_t i = 0; i < scene.boxes.size(); ++i) {
    scene.boxes[i].color_class = i % 2 ? "red" : "blue";
    scene.boxes[i].y_m *= 0.4;
  }
  const ColorTable table({test::makeClass("red", ColorSpace::YUV, {{0, 0, 0}}, {{0, 0, 0}}),
                          test::makeClass("blue", ColorSpace::YUV, {{0, 0, 0}}, {{0, 0, 0}})});
  const SceneSimulator simulator(scene);
  int merged = 0;
  for (int frame = 0; frame < 60; frame += 6) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    const std::vector<BoxTruth> isolated = test::isolatedBoxes(f, table);
    for (const BoxTruth& box : f.boxes) {
      if (box.area == 0) continue;
      const bool whole = std::any_of(isolated.begin(), isolated.end(), [&](const BoxTruth& b) { return b.name == box.name; });
      EXPECT_EQ(whole, box.pieces == 1 && !box.touches_same_class) << box.name << " frame " << frame;
      merged += box.touches_same_class;
    }
  }
  EXPECT_GT(merged, 0) << "the crowded scene should make same-colour boxes touch";
}

TEST(SceneSimulator, BoxStraightAheadIsCentredAndNearerBoxesAreLower) {
  SceneConfig scene = defaultScene();
  scene.gait_roll_amplitude_deg = scene.gait_pitch_amplitude_deg = scene.gait_yaw_amplitude_deg = 0;
  scene.gait_bob_amplitude_m = 0;
  scene.boxes.resize(2);
  scene.boxes[0] = SceneBox{"near", "red", {{210, 40, 40}}, 1.0, 0.0, 0.2, 0.2, 0.3, 0, 0, 0, 0, 0, 0};
  scene.boxes[1] = SceneBox{"far", "red", {{210, 40, 40}}, 3.0, 0.0, 0.2, 0.2, 0.3, 0, 0, 0, 0, 0, 0};
  const SceneSimulator simulator(scene);
  const SimFrame f = simulator.render(0, 0);
  const PinholeCamera& camera = simulator.camera();
  for (const BoxTruth& box : f.boxes) {
    // Mirror symmetric about the image centre column x = cx - 0.5 (pixel centres are integers).
    EXPECT_NEAR(box.cx, camera.cx - 0.5, 0.51) << box.name;
  }
  EXPECT_GT(f.boxes[0].bottom, f.boxes[1].bottom);
  EXPECT_GT(f.boxes[0].area, 4 * f.boxes[1].area);
  // The near box's front bottom edge at x = 0.9 m projects where the pinhole model says.
  const double depth = 0.9, drop = 0.45, pitch = 20 * M_PI / 180;
  const double angle_below_axis = std::atan2(drop, depth) - pitch;
  const double expected_v = camera.cy + camera.fy * std::tan(angle_below_axis);
  EXPECT_NEAR(f.boxes[0].bottom, expected_v, 1.0);
}

TEST(SceneSimulator, SameFrameIsIdenticalAndSeedsDiffer) {
  SceneConfig scene = defaultScene();
  scene.noise_sigma = 4;
  const SceneSimulator a(scene);
  const SimFrame f1 = a.render(7, 0.2), f2 = a.render(7, 0.2), f3 = a.render(8, 0.2);
  EXPECT_EQ(cv::norm(f1.image, f2.image, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(f1.image, f3.image, cv::NORM_INF), 0.0);
  scene.seed += 1;
  EXPECT_GT(cv::norm(f1.image, SceneSimulator(scene).render(7, 0.2).image, cv::NORM_INF), 0.0);
}

TEST(SceneSimulator, NoiseHasTheConfiguredSigma) {
  SceneConfig scene = defaultScene();
  scene.boxes.clear();
  scene.blur_sigma_px = 0;
  scene.noise_sigma = 5;
  SceneConfig clean = scene;
  clean.noise_sigma = 0;
  cv::Mat noisy, flat;
  SceneSimulator(scene).render(1, 0).image.convertTo(noisy, CV_32FC3);
  SceneSimulator(clean).render(1, 0).image.convertTo(flat, CV_32FC3);
  cv::Scalar mean, stddev;
  cv::meanStdDev(noisy - flat, mean, stddev);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(stddev[c], 5.0, 0.15);
    EXPECT_NEAR(mean[c], 0.0, 0.1);
  }
}

TEST(SensorNoise, TableIsTheRoundedGaussian) {
  for (double sigma : {0.3, 2.0, 25.0, 60.0}) {
    const std::vector<int16_t> table = roundedGaussianTable(sigma);
    ASSERT_EQ(table.size(), 65536u);
    EXPECT_TRUE(std::is_sorted(table.begin(), table.end()));
    double sum = 0, sum_sq = 0;
    for (int16_t v : table) {
      sum += v;
      sum_sq += double(v) * v;
    }
    const double mean = sum / table.size();
    // The variance of round(N(0, sigma)), summed over whole levels; the cut tails take ~0.1%.
    double variance = 0;
    for (int k = 1; k <= 10 * sigma + 2; ++k) {
      variance += 2.0 * k * k * 0.5 * (std::erfc((k - 0.5) / (sigma * M_SQRT2)) - std::erfc((k + 0.5) / (sigma * M_SQRT2)));
    }
    EXPECT_NEAR(mean, 0.0, 1e-3 * sigma + 1e-3) << sigma;
    EXPECT_NEAR(std::sqrt(sum_sq / table.size() - mean * mean), std::sqrt(variance), 0.005 * sigma + 0.005) << sigma;
    // Symmetric: entry i and entry 65535 - i are opposite values.
    for (size_t i = 0; i < table.size(); i += 97) EXPECT_EQ(table[i], -table[table.size() - 1 - i]) << sigma;
  }
  EXPECT_THROW(roundedGaussianTable(0), std::invalid_argument);
  EXPECT_THROW(roundedGaussianTable(std::nan("")), std::invalid_argument);
}

TEST(SensorNoise, SaturatesRepeatsForASeedAndIsUncorrelated) {
  cv::Mat dark(120, 160, CV_8UC3, cv::Scalar(0, 128, 255)), a = dark.clone(), b = dark.clone(), c = dark.clone();
  addGaussianNoise(20, 5, &a);
  addGaussianNoise(20, 5, &b);
  addGaussianNoise(20, 6, &c);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_INF), 0.0);
  std::vector<cv::Mat> channels;
  cv::split(a, channels);
  // Black can only get brighter and white darker: about half of each clips.
  EXPECT_NEAR(cv::countNonZero(channels[0] == 0) / double(a.total()), 0.5, 0.03);
  EXPECT_NEAR(cv::countNonZero(channels[2] == 255) / double(a.total()), 0.5, 0.03);
  // Mid grey: neighbouring values (the four from one hash) and two seeds are uncorrelated.
  cv::Mat grey_a, grey_c, left, right;
  channels[1].convertTo(grey_a, CV_64F, 1, -128);
  std::vector<cv::Mat> other;
  cv::split(c, other);
  other[1].convertTo(grey_c, CV_64F, 1, -128);
  const double var = grey_a.dot(grey_a) / grey_a.total();
  EXPECT_NEAR(std::sqrt(var), 20.0, 0.6);
  EXPECT_LT(std::abs(grey_a.dot(grey_c) / grey_a.total() / var), 0.03);
  left = grey_a.colRange(0, 159);
  right = grey_a.colRange(1, 160);
  EXPECT_LT(std::abs(left.dot(right) / left.total() / var), 0.03);
  cv::Mat wide(4, 4, CV_16UC1);
  EXPECT_THROW(addGaussianNoise(2, 1, &wide), std::invalid_argument);
  // A table built once (as the simulator does) gives the same noise; a table of another size is refused.
  cv::Mat d = dark.clone();
  addGaussianNoise(roundedGaussianTable(20), 5, &d);
  EXPECT_EQ(cv::norm(a, d, cv::NORM_INF), 0.0);
  EXPECT_THROW(addGaussianNoise(std::vector<int16_t>(100, 0), 5, &d), std::invalid_argument);
}

TEST(SceneSimulator, GaitSwayAndLightingDrift) {
  SceneConfig scene = defaultScene();
  scene.light_gain_end = 0.55;
  scene.light_drift_duration_s = 30;
  const SceneSimulator simulator(scene);
  EXPECT_NEAR(simulator.lightGainAt(0), 1.0, 1e-12);
  EXPECT_NEAR(simulator.lightGainAt(15), 0.775, 1e-12);
  EXPECT_NEAR(simulator.lightGainAt(60), 0.55, 1e-12);
  const CameraPose quarter = simulator.poseAt(0.25);  // quarter stride at 1 Hz: peak roll
  EXPECT_NEAR(quarter.roll, 3 * M_PI / 180, 1e-12);
  EXPECT_NEAR(quarter.pitch, 20 * M_PI / 180, 1e-12);
  const cv::Scalar early = cv::mean(simulator.render(0, 0).image);
  const cv::Scalar late = cv::mean(simulator.render(900, 30).image);
  EXPECT_NEAR(late[1] / early[1], 0.55, 0.02);
}

TEST(SceneSimulator, RejectsUnusableConfigurations) {
  SceneConfig scene = defaultScene();
  scene.camera_height_m = -1;
  EXPECT_THROW(SceneSimulator{scene}, std::invalid_argument);
  scene = defaultScene();
  scene.hfov_deg = std::nan("");
  EXPECT_THROW(SceneSimulator{scene}, std::invalid_argument);
  scene = defaultScene();
  scene.boxes[0].height_m = 0;
  EXPECT_THROW(SceneSimulator{scene}, std::invalid_argument);
  scene = defaultScene();
  scene.has_field = true;
  scene.field_x_min_m = 3;
  scene.field_x_max_m = 2;  // an empty field
  EXPECT_THROW(SceneSimulator{scene}, std::invalid_argument);
}

TEST(SceneSimulator, AFieldsFloorEndsWhereItsTruthSays) {
  // Without a field no column has a field top; with one (its far edge below the horizon in
  // every column), each column's top pixel is the carpet's and the one above it the hall's floor.
  const SimFrame plain = SceneSimulator(defaultScene()).render(0, 0);
  EXPECT_TRUE(plain.field_top.empty());
  SceneConfig scene = defaultScene();
  scene.boxes.clear();
  scene.noise_sigma = 0;
  scene.blur_sigma_px = 0;
  scene.ground_texture_contrast = 0;
  scene.has_field = true;
  scene.field_x_min_m = -1;
  scene.field_x_max_m = 4;
  scene.field_y_min_m = -1.5;
  scene.field_y_max_m = 1.5;
  const SimFrame frame = SceneSimulator(scene).render(0, 0);
  ASSERT_EQ(frame.field_top.size(), static_cast<size_t>(scene.width));
  const cv::Vec3b carpet = frame.image.at<cv::Vec3b>(frame.image.rows - 1, frame.image.cols / 2);
  const cv::Vec3b surround(scene.surround_rgb[2], scene.surround_rgb[1], scene.surround_rgb[0]);
  for (int u = 0; u < scene.width; u += 16) {
    ASSERT_FALSE(std::isnan(frame.field_top[u])) << "column " << u;
    const int top = static_cast<int>(frame.field_top[u]);
    EXPECT_EQ(frame.image.at<cv::Vec3b>(top, u), carpet) << "column " << u;
    ASSERT_GT(top, 0);
    EXPECT_EQ(frame.image.at<cv::Vec3b>(top - 1, u), surround) << "column " << u;
  }
}

TEST(SceneSimulator, CameraInsideABoxDoesNotCrash) {
  SceneConfig scene = defaultScene();
  scene.boxes[0].x_m = 0;
  scene.boxes[0].y_m = 0;
  scene.boxes[0].height_m = 2;
  const SimFrame f = SceneSimulator(scene).render(0, 0);
  EXPECT_EQ(f.image.size(), cv::Size(640, 480));
}

}  // namespace
}  // namespace rle_vision
