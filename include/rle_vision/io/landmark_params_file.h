// Landmark parameter files: the keys of landmark_params.def (the Landmark node's parameters,
// the EdgeDetector's edge_gain, and the ROS-only start-up parameter low_priority). Missing
// keys keep their defaults; values are checked against the table's types and limits, and the
// result is validated. Errors name the file, the line and the reason (ConfigError).
#pragma once

#include <string>

#include "rle_vision/field/field_detector.h"
#include "rle_vision/learning/color_learning.h"
#include "rle_vision/learning/color_learning_loop.h"
#include "rle_vision/io/config_error.h"
#include "rle_vision/landmark/landmark_detector.h"

namespace rle_vision {

LandmarkOptions loadLandmarkParams(const std::string& path);
LandmarkOptions parseLandmarkParams(const std::string& text, const std::string& origin);

// Colour learning's parameters (the learning_* keys) from the same file.
LearningOptions loadLearningParams(const std::string& path);
LearningOptions parseLearningParams(const std::string& text, const std::string& origin);

// The learning loop's (`learning`, `learning_publish_period_s`) from the same file.
LearningLoopOptions loadLearningLoopParams(const std::string& path);
LearningLoopOptions parseLearningLoopParams(const std::string& text, const std::string& origin);

// The field stage's (the field_* keys) from the same file.
FieldOptions loadFieldParams(const std::string& path);
FieldOptions parseFieldParams(const std::string& text, const std::string& origin);

// A parameters file holding every key with its default, limits and meaning (comments).
std::string defaultLandmarkParamsYaml();

}  // namespace rle_vision
