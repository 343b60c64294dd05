// Horizon model files (config/horizon_model.yaml): the features the model reads, in order, their
// standardisation, the weights and the bias, and a comment saying how the model was made.
// Errors name the file, the line and the reason (ConfigError).
#pragma once

#include <string>

#include "rle_vision/io/config_error.h"
#include "rle_vision/landmark/horizon_model.h"

namespace rle_vision {

HorizonModel loadHorizonModel(const std::string& path);
HorizonModel parseHorizonModel(const std::string& text, const std::string& origin);
// The model a node or tool uses: "" the package's config/horizon_model.yaml (none when it is
// not found: the evidence product), "none" no model, else the file named.
HorizonModel horizonModelFromSetting(const std::string& setting);

// The model as a file; `provenance` goes into its first comment lines (how it was made).
std::string horizonModelYaml(const HorizonModel& model, const std::string& provenance);

}  // namespace rle_vision
