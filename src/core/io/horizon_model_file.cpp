#include "rle_vision/io/horizon_model_file.h"

#include <iomanip>
#include <sstream>
#include <vector>

#include "io/yaml_reader.h"
#include "rle_vision/io/data_files.h"

namespace rle_vision {
namespace {

// One list of kHorizonFeatureCount finite numbers.
void readList(const std::string& origin, const YAML::Node& root, const char* key, HorizonFeatures* out) {
  const YAML::Node list = root[key];
  if (!list || !list.IsSequence() || list.size() != static_cast<size_t>(kHorizonFeatureCount)) {
    yaml_reader::fail(origin, list ? list : root,
                      std::string("'") + key + "' must be a list of " + std::to_string(kHorizonFeatureCount) + " numbers");
  }
  for (int f = 0; f < kHorizonFeatureCount; ++f) {
    try {
      (*out)[f] = list[f].as<double>();
    } catch (const YAML::Exception&) {
      yaml_reader::fail(origin, list[f], std::string("'") + key + "' holds something that is not a number");
    }
    if (!std::isfinite((*out)[f])) yaml_reader::fail(origin, list[f], std::string("'") + key + "' holds a non-finite number");
  }
}

}  // namespace

HorizonModel parseHorizonModel(const std::string& text, const std::string& origin) {
  const YAML::Node root = yaml_reader::parse(text, origin);
  if (!root || !root.IsMap()) yaml_reader::fail(origin, 1, "expected a mapping with features, mean, scale, weights, bias");
  yaml_reader::checkKeys(origin, root, {"features", "mean", "scale", "weights", "bias", "stop_probability"});
  const YAML::Node names = root["features"];
  if (!names || !names.IsSequence() || names.size() != static_cast<size_t>(kHorizonFeatureCount)) {
    yaml_reader::fail(origin, names ? names : root,
                      "'features' must list the " + std::to_string(kHorizonFeatureCount) + " features this build reads");
  }
  for (int f = 0; f < kHorizonFeatureCount; ++f) {
    if (names[f].as<std::string>("") != horizonFeatureName(f)) {
      yaml_reader::fail(origin, names[f], "feature " + std::to_string(f + 1) + " must be '" + horizonFeatureName(f) +
                                              "' (the model was made for another build: train it again)");
    }
  }
  HorizonModel m;
  readList(origin, root, "mean", &m.mean);
  readList(origin, root, "scale", &m.scale);
  readList(origin, root, "weights", &m.weights);
  for (int f = 0; f < kHorizonFeatureCount; ++f) {
    if (m.scale[f] <= 0) yaml_reader::fail(origin, root["scale"][f], "'scale' must be positive");
  }
  if (!root["bias"]) yaml_reader::fail(origin, root, "'bias' is missing");
  m.bias = yaml_reader::number(origin, root, "bias", 0);
  if (root["stop_probability"]) {  // files made before it: every candidate weighed
    m.stop_probability = yaml_reader::number(origin, root, "stop_probability", 2);
    if (!(m.stop_probability >= 0.5)) {
      yaml_reader::fail(origin, root["stop_probability"], "'stop_probability' must be 0.5 or more (above 1: weigh every candidate)");
    }
  }
  m.valid = true;
  return m;
}

HorizonModel loadHorizonModel(const std::string& path) { return parseHorizonModel(yaml_reader::readFile(path), path); }

HorizonModel horizonModelFromSetting(const std::string& setting) {
  if (setting == "none") return HorizonModel();
  if (!setting.empty()) return loadHorizonModel(setting);
  const std::string shipped = packageDataFile("config/horizon_model.yaml");
  return shipped.empty() ? HorizonModel() : loadHorizonModel(shipped);
}

std::string horizonModelYaml(const HorizonModel& m, const std::string& provenance) {
  std::ostringstream yaml;
  std::istringstream lines(provenance);
  for (std::string line; std::getline(lines, line);) yaml << "# " << line << "\n";
  auto list = [&yaml](const char* key, const HorizonFeatures& values) {
    yaml << key << ": [";
    for (int f = 0; f < kHorizonFeatureCount; ++f) yaml << (f ? ", " : "") << std::setprecision(9) << values[f];
    yaml << "]\n";
  };
  yaml << "features: [";
  for (int f = 0; f < kHorizonFeatureCount; ++f) yaml << (f ? ", " : "") << horizonFeatureName(f);
  yaml << "]\n";
  list("mean", m.mean);
  list("scale", m.scale);
  list("weights", m.weights);
  yaml << "bias: " << std::setprecision(9) << m.bias << "\n";
  if (m.stop_probability <= 1) yaml << "stop_probability: " << std::setprecision(9) << m.stop_probability << "\n";
  return yaml.str();
}

}  // namespace rle_vision
