// The frame every tracker benchmark and the agreement test use: the built-in scene
// (640x480, ten boxes of four colour classes, sensor noise) at t = 0.
#pragma once

#include <string>

#include "rle_vision/io/color_config.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"

namespace rle_vision {

inline SimFrame benchmarkFrame(const std::string& source_dir) {
  const SceneSimulator simulator(loadSceneConfig(source_dir + "/config/scene_default.yaml"));
  return simulator.render(0, 0.0);
}

inline std::vector<ColorClass> benchmarkClasses(const std::string& source_dir) {
  return loadColorClasses(source_dir + "/config/colors.yaml");
}

}  // namespace rle_vision
