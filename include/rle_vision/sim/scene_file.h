// Simulator scene files (see config/scene_default.yaml). Errors name the file, the line and
// the reason (ConfigError).
#pragma once

#include <string>

#include "rle_vision/io/config_error.h"
#include "rle_vision/sim/scene_simulator.h"

namespace rle_vision {

SceneConfig loadSceneConfig(const std::string& path);
SceneConfig parseSceneConfig(const std::string& text, const std::string& origin);

}  // namespace rle_vision
