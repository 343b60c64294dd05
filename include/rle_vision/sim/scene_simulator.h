// A ROS-free renderer of the biped robot's camera view with exact ground truth: flat ground,
// sky above the horizon, coloured boxes standing on the ground, a camera that sways like a
// walking gait, optional lighting drift and seeded Gaussian sensor noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "rle_vision/ground/camera_model.h"
#include "rle_vision/color/color_class.h"
#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {

struct SceneBox {
  std::string name;
  std::string color_class;  // the colour class the tracker should report it as
  Channels rgb{{200, 30, 30}};
  double x_m = 1.0, y_m = 0.0;  // footprint centre at t = 0, base frame, m
  double depth_m = 0.2;         // extent along the box's own x axis, m
  double width_m = 0.2;         // extent along the box's own y axis, m
  double height_m = 0.3;        // m
  double yaw_deg = 0;
  double vx_mps = 0, vy_mps = 0;  // constant drift, m/s
  double sway_x_m = 0, sway_y_m = 0, sway_period_s = 0;  // sinusoidal motion (0 period: none)
};

struct SceneConfig {
  int width = 640, height = 480;  // px
  double hfov_deg = 70;
  double camera_height_m = 0.45;
  double camera_pitch_deg = 20;  // nose down
  double camera_roll_deg = 0;
  double camera_yaw_deg = 0;
  // Walking gait sway: roll and yaw once per stride, pitch and bob twice per stride.
  double gait_frequency_hz = 1.0;
  double gait_roll_amplitude_deg = 3;
  double gait_pitch_amplitude_deg = 2;
  double gait_yaw_amplitude_deg = 2;
  double gait_bob_amplitude_m = 0.01;
  Channels ground_rgb{{40, 140, 50}};
  // Real ground is textured (grass, carpet, soil): its brightness varies by up to
  // +-ground_texture_contrast (a share) in blotches of ground_texture_grain_m, fixed on the
  // ground, fading where a pixel covers several blotches (far away). 0: flat colour.
  double ground_texture_contrast = 0;
  double ground_texture_grain_m = 0.03;
  Channels sky_rgb{{150, 200, 240}};
  // A field: the ground colour only inside x in [field_x_min_m, field_x_max_m], y in
  // [field_y_min_m, field_y_max_m] (base frame at the start pose), surround_rgb outside (the
  // hall's floor). Without one the ground colour runs to the horizon.
  bool has_field = false;
  double field_x_min_m = 0, field_x_max_m = 0, field_y_min_m = 0, field_y_max_m = 0;
  Channels surround_rgb{{150, 120, 90}};
  // Lighting: gain and per-channel colour cast move linearly from start to end over
  // drift_duration_s, then hold (0 duration: no drift).
  double light_gain_start = 1.0, light_gain_end = 1.0;
  std::array<double, 3> light_cast_start_rgb{{1.0, 1.0, 1.0}};
  std::array<double, 3> light_cast_end_rgb{{1.0, 1.0, 1.0}};
  double light_drift_duration_s = 0;
  bool antialias = true;     // blend polygon edge pixels (the image then holds sub-pixel edge positions)
  double blur_sigma_px = 0;  // Gaussian lens blur, px (0: no blur)
  double noise_sigma = 0;    // Gaussian sensor noise, per channel, 8-bit units
  uint64_t seed = 1;
  std::vector<SceneBox> boxes;
};

struct CameraPose {
  double roll = 0, pitch = 0, yaw = 0;  // rad, REP 103, pitch positive = nose down
  double x_m = 0, y_m = 0, height_m = 0;
};

struct BoxTruth {
  std::string name, color_class;
  uint8_t label = 0;  // value in SimFrame::labels
  uint32_t area = 0;  // visible pixels
  double cx = 0, cy = 0;
  int left = 0, top = 0, right = -1, bottom = -1;  // inclusive; right < left when not visible
  int pieces = 0;  // 8-connected pieces of the visible mask (an occluder in front can split it)
  bool touches_same_class = false;  // its mask touches a box of the same colour class
  bool touches_other_box = false;   // its mask touches any other box (occluding or occluded)
  Eigen::Vector2d position_m{0, 0};  // footprint centre, base frame
  double width_m = 0, depth_m = 0, height_m = 0, yaw_rad = 0;
};

// A straight edge visible in the rendered image: a stretch of a box edge (silhouette or the
// fold between two faces) or of the horizon with enough contrast across it, cut where it is
// hidden or where the contrast fades.
struct EdgeTruth {
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // px
  int box = -1;                           // box index, -1 for the horizon
  double contrast = 0;                    // smallest max-channel colour step along it (8-bit units)
};

struct SimFrame {
  uint64_t frame_index = 0;
  double time_s = 0;
  cv::Mat image;   // CV_8UC3 BGR
  cv::Mat labels;  // CV_8UC1: kGroundLabel, kSkyLabel, or kFirstBoxLabel + box index
  std::vector<BoxTruth> boxes;
  std::vector<EdgeTruth> edges;  // visible straight edges with contrast >= kMinEdgeContrast
  // Every visible straight edge down to a faint step (contrast >= kMinFaintContrast): a line
  // detected along one of these is on a real edge of the scene, however weak.
  std::vector<EdgeTruth> faint_edges;
  ImageLine horizon;
  bool horizon_visible = false;
  // With a field: per image column, the topmost row whose pixel centre sees the field's floor
  // (boxes in front of it not counted: the field boundary's exact position); NaN where the
  // column sees none of it.
  std::vector<float> field_top;
  CameraPose pose;
  double light_gain = 1.0;
};

class SceneSimulator {
 public:
  static constexpr uint8_t kGroundLabel = 0;
  static constexpr uint8_t kSkyLabel = 1;
  static constexpr uint8_t kFirstBoxLabel = 2;
  // Colour step (largest channel difference, 8-bit units) that makes an edge count as visible.
  static constexpr double kMinEdgeContrast = 30;
  static constexpr double kMinFaintContrast = 6;

  // Throws std::invalid_argument when the configuration is unusable (the reason says why).
  explicit SceneSimulator(const SceneConfig& config);
  const SceneConfig& config() const { return config_; }
  const PinholeCamera& camera() const { return camera_; }

  CameraPose poseAt(double time_s) const;
  double lightGainAt(double time_s) const;
  Eigen::Vector2d boxPositionAt(const SceneBox& box, double time_s) const;
  // Deterministic: the same (frame_index, time_s) always gives the same frame.
  SimFrame render(uint64_t frame_index, double time_s) const;

 private:
  SceneConfig config_;
  PinholeCamera camera_;
  std::vector<float> texture_lattice_;  // the ground texture's random values, kTextureLattice^2
  std::vector<int16_t> noise_table_;    // roundedGaussianTable(noise_sigma); empty without noise
};

// Reason the configuration is unusable, or "" when it is fine.
std::string validateSceneConfig(const SceneConfig& config);

}  // namespace rle_vision
