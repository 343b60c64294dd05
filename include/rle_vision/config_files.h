// Reading colour classes and simulator scenes from files. Every error names the file, the
// line and the reason, e.g. "config/colors.yaml:12: 'min' must be a list of 3 integers 0..255".
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "rle_vision/color_class.h"
#include "rle_vision/color_learning.h"
#include "rle_vision/landmark_detector.h"
#include "rle_vision/scene_simulator.h"

namespace rle_vision {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// colors.yaml (see config/colors.yaml) or a CMVision colors.txt ([Colors] and [Thresholds]
// sections; the format is chosen by content, not by name). Throws ConfigError.
std::vector<ColorClass> loadColorClasses(const std::string& path);
std::vector<ColorClass> parseColorClassesYaml(const std::string& text, const std::string& origin);
std::vector<ColorClass> parseCmvisionColors(const std::string& text, const std::string& origin);

// Writes classes as colors.yaml text (loadColorClasses reads it back unchanged).
std::string colorClassesToYaml(const std::vector<ColorClass>& classes);

// Landmark parameters (see config/landmark.yaml; the names of the Landmark nodelet's
// parameters, plus the EdgeDetector's edge_gain). Missing keys keep their defaults; the
// result is validated. Throws ConfigError.
LandmarkOptions loadLandmarkParams(const std::string& path);
LandmarkOptions parseLandmarkParams(const std::string& text, const std::string& origin);

// Colour learning's parameters (the learning_* keys) from the same file. Throws ConfigError.
LearningOptions loadLearningParams(const std::string& path);
LearningOptions parseLearningParams(const std::string& text, const std::string& origin);

// A scene file (see config/scene_default.yaml). Throws ConfigError.
SceneConfig loadSceneConfig(const std::string& path);
SceneConfig parseSceneConfig(const std::string& text, const std::string& origin);

}  // namespace rle_vision
