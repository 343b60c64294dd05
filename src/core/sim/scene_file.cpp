
#include "rle_vision/sim/scene_file.h"
#include "io/yaml_reader.h"

namespace rle_vision {

namespace {

using namespace yaml_reader;

void readCamera(const std::string& origin, const YAML::Node& root, SceneConfig* c) {
  if (const YAML::Node image = root["image"]) {
    checkKeys(origin, image, {"width", "height"});
    c->width = static_cast<int>(number(origin, image, "width", c->width, 2, 8192));
    c->height = static_cast<int>(number(origin, image, "height", c->height, 2, 8192));
  }
  if (const YAML::Node cam = root["camera"]) {
    checkKeys(origin, cam, {"hfov_deg", "height_m", "pitch_deg", "roll_deg", "yaw_deg"});
    c->hfov_deg = number(origin, cam, "hfov_deg", c->hfov_deg, 1.01, 178.99);
    c->camera_height_m = number(origin, cam, "height_m", c->camera_height_m, 0.03, 100);
    c->camera_pitch_deg = number(origin, cam, "pitch_deg", c->camera_pitch_deg, -89, 89);
    c->camera_roll_deg = number(origin, cam, "roll_deg", c->camera_roll_deg, -89, 89);
    c->camera_yaw_deg = number(origin, cam, "yaw_deg", c->camera_yaw_deg, -180, 180);
  }
  if (const YAML::Node gait = root["gait"]) {
    checkKeys(origin, gait, {"frequency_hz", "roll_amplitude_deg", "pitch_amplitude_deg",
                             "yaw_amplitude_deg", "bob_amplitude_m"});
    c->gait_frequency_hz = number(origin, gait, "frequency_hz", c->gait_frequency_hz, 0, 20);
    c->gait_roll_amplitude_deg = number(origin, gait, "roll_amplitude_deg", c->gait_roll_amplitude_deg, 0, 45);
    c->gait_pitch_amplitude_deg = number(origin, gait, "pitch_amplitude_deg", c->gait_pitch_amplitude_deg, 0, 45);
    c->gait_yaw_amplitude_deg = number(origin, gait, "yaw_amplitude_deg", c->gait_yaw_amplitude_deg, 0, 45);
    c->gait_bob_amplitude_m = number(origin, gait, "bob_amplitude_m", c->gait_bob_amplitude_m, 0, 1);
  }
}

void readWorld(const std::string& origin, const YAML::Node& root, SceneConfig* c) {
  c->ground_rgb = triple<uint8_t>(origin, root, "ground_rgb", c->ground_rgb, 0, 255, "integers 0..255");
  if (const YAML::Node texture = root["ground_texture"]) {
    checkKeys(origin, texture, {"contrast", "grain_m"});
    c->ground_texture_contrast = number(origin, texture, "contrast", c->ground_texture_contrast, 0, 1);
    c->ground_texture_grain_m = number(origin, texture, "grain_m", c->ground_texture_grain_m, 1e-4, 10);
  }
  c->sky_rgb = triple<uint8_t>(origin, root, "sky_rgb", c->sky_rgb, 0, 255, "integers 0..255");
  if (const YAML::Node field = root["field"]) {
    checkKeys(origin, field, {"x_min_m", "x_max_m", "y_min_m", "y_max_m", "surround_rgb"});
    c->has_field = true;
    c->field_x_min_m = number(origin, field, "x_min_m", -1.0, -1e4, 1e4);
    c->field_x_max_m = number(origin, field, "x_max_m", 10.0, -1e4, 1e4);
    c->field_y_min_m = number(origin, field, "y_min_m", -5.0, -1e4, 1e4);
    c->field_y_max_m = number(origin, field, "y_max_m", 5.0, -1e4, 1e4);
    c->surround_rgb = triple<uint8_t>(origin, field, "surround_rgb", c->surround_rgb, 0, 255, "integers 0..255");
  }
  if (const YAML::Node light = root["lighting"]) {
    checkKeys(origin, light, {"gain_start", "gain_end", "cast_start_rgb", "cast_end_rgb", "drift_duration_s"});
    c->light_gain_start = number(origin, light, "gain_start", c->light_gain_start, 0, 10);
    c->light_gain_end = number(origin, light, "gain_end", c->light_gain_end, 0, 10);
    c->light_cast_start_rgb = triple<double>(origin, light, "cast_start_rgb", c->light_cast_start_rgb, 0, 10, "numbers 0..10");
    c->light_cast_end_rgb = triple<double>(origin, light, "cast_end_rgb", c->light_cast_end_rgb, 0, 10, "numbers 0..10");
    c->light_drift_duration_s = number(origin, light, "drift_duration_s", c->light_drift_duration_s, 0, 1e6);
  }
}

void readSensor(const std::string& origin, const YAML::Node& root, SceneConfig* c) {
  const YAML::Node sensor = root["sensor"];
  if (!sensor) return;
  checkKeys(origin, sensor, {"noise_sigma", "blur_sigma_px", "seed", "antialias"});
  if (const YAML::Node aa = sensor["antialias"]) {
    try {
      c->antialias = aa.as<bool>();
    } catch (const YAML::Exception&) {
      fail(origin, aa, "'antialias' must be true or false");
    }
  }
  c->noise_sigma = number(origin, sensor, "noise_sigma", c->noise_sigma, 0, 128);
  c->blur_sigma_px = number(origin, sensor, "blur_sigma_px", c->blur_sigma_px, 0, 20);
  c->seed = static_cast<uint64_t>(number(origin, sensor, "seed", static_cast<double>(c->seed), 0, 1e15));
}

SceneBox readBox(const std::string& origin, const YAML::Node& node, size_t index) {
  checkKeys(origin, node, {"name", "color", "rgb", "x_m", "y_m", "depth_m", "width_m", "height_m",
                           "yaw_deg", "vx_mps", "vy_mps", "sway_x_m", "sway_y_m", "sway_period_s"});
  SceneBox b;
  b.name = stringValue(origin, node, "name", "box_" + std::to_string(index));
  b.color_class = stringValue(origin, node, "color", "");
  b.rgb = triple<uint8_t>(origin, node, "rgb", b.rgb, 0, 255, "integers 0..255");
  b.x_m = number(origin, node, "x_m", b.x_m, -1000, 1000);
  b.y_m = number(origin, node, "y_m", b.y_m, -1000, 1000);
  b.depth_m = number(origin, node, "depth_m", b.depth_m, 1e-3, 100);
  b.width_m = number(origin, node, "width_m", b.width_m, 1e-3, 100);
  b.height_m = number(origin, node, "height_m", b.height_m, 1e-3, 100);
  b.yaw_deg = number(origin, node, "yaw_deg", b.yaw_deg, -360, 360);
  b.vx_mps = number(origin, node, "vx_mps", b.vx_mps, -100, 100);
  b.vy_mps = number(origin, node, "vy_mps", b.vy_mps, -100, 100);
  b.sway_x_m = number(origin, node, "sway_x_m", b.sway_x_m, -100, 100);
  b.sway_y_m = number(origin, node, "sway_y_m", b.sway_y_m, -100, 100);
  b.sway_period_s = number(origin, node, "sway_period_s", b.sway_period_s, 0, 1e6);
  return b;
}

}  // namespace

SceneConfig parseSceneConfig(const std::string& source, const std::string& origin) {
  const YAML::Node root = parse(source, origin);
  if (!root.IsMap()) fail(origin, root, "a scene file must be a mapping (image:, camera:, boxes: ...)");
  checkKeys(origin, root, {"image", "camera", "gait", "ground_rgb", "ground_texture", "sky_rgb", "field", "lighting", "sensor",
                              "boxes"});
  SceneConfig c;
  readCamera(origin, root, &c);
  readWorld(origin, root, &c);
  readSensor(origin, root, &c);
  if (const YAML::Node boxes = root["boxes"]) {
    if (!boxes.IsSequence()) fail(origin, boxes, "'boxes' must be a list");
    for (const YAML::Node& node : boxes) c.boxes.push_back(readBox(origin, node, c.boxes.size()));
  }
  const std::string problem = validateSceneConfig(c);
  if (!problem.empty()) fail(origin, root, problem);
  return c;
}

SceneConfig loadSceneConfig(const std::string& path) { return parseSceneConfig(yaml_reader::readFile(path), path); }

}  // namespace rle_vision
