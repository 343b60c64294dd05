// Landmark parameter files: the keys, types, limits and defaults of landmark_params.def.
#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "rle_vision/io/landmark_params_file.h"
#include "io/yaml_reader.h"

namespace rle_vision {
namespace {

// Every key of a landmark parameters file: the table's, and the ROS-only start-up parameter
// low_priority.
const std::vector<std::string>& landmarkFileKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> all{"low_priority"};
#define RLE_KEY(key, member, type, default_value, min, max, description) all.push_back(#key);
#define RLE_EDGE_PARAM RLE_KEY
#define RLE_OBJECTS_PARAM RLE_KEY
#define RLE_HOUGH_PARAM RLE_KEY
#define RLE_HORIZON_PARAM RLE_KEY
#define RLE_LEARNING_PARAM RLE_KEY
#define RLE_LEARNING_LOOP_PARAM RLE_KEY
#define RLE_FIELD_COLOR_PARAM RLE_KEY
#define RLE_FIELD_BOUNDARY_PARAM RLE_KEY
#include "rle_vision/params/landmark_params.def"
#undef RLE_KEY
    return all;
  }();
  return keys;
}

// One parameter into `member` when the file has it, checked against the table's type and limits.
template <typename T>
void read(const std::string& origin, const YAML::Node& map, const char* key, T* member, double lo, double hi) {
  const YAML::Node node = map[key];
  if (!node) return;
  if constexpr (std::is_same<T, bool>::value) {
    try {
      *member = node.as<bool>();
    } catch (const YAML::Exception&) {
      yaml_reader::fail(origin, node, std::string("'") + key + "' must be true or false");
    }
  } else {
    const double value = yaml_reader::number(origin, map, key, 0, lo, hi);
    if (std::is_integral<T>::value && value != std::floor(value)) {
      yaml_reader::fail(origin, node, std::string("'") + key + "' must be a whole number");
    }
    *member = static_cast<T>(value);
  }
}

// A default value as YAML writes it (bools are spelled out by the caller).
// The shortest text that reads back as the same double (0.4, not 0.40000000000000002).
std::string yamlNumber(double value) {
  for (int precision = 15; precision <= 17; ++precision) {
    std::ostringstream text;
    text.precision(precision);
    text << value;
    if (precision == 17 || std::stod(text.str()) == value) return text.str();
  }
  return {};
}

YAML::Node parseChecked(const std::string& text, const std::string& origin) {
  const YAML::Node root = yaml_reader::parse(text, origin);
  if (root && !root.IsNull()) yaml_reader::checkKeys(origin, root, landmarkFileKeys());
  return root;
}

}  // namespace

std::string defaultLandmarkParamsYaml() {
  std::ostringstream yaml;
  yaml << "# Landmark parameters (rle_vision/Landmark; edge_gain: rle_vision/EdgeDetector), with their\n"
          "# defaults. Units are in the names; [min, max] are the limits.\n";
  auto entry = [&yaml](const char* key, const std::string& value, const char* range, const char* description) {
    yaml << key << ": " << value << "  # " << description << " " << range << "\n";
  };
#define RLE_ENTRY(key, member, type, default_value, min, max, description)                                   \
  entry(#key, std::is_same<type, bool>::value ? std::string(#default_value) : yamlNumber(default_value),  \
        std::is_same<type, bool>::value ? "" : "[" #min ", " #max "]", description);
#define RLE_EDGE_PARAM RLE_ENTRY
#define RLE_OBJECTS_PARAM RLE_ENTRY
#define RLE_HOUGH_PARAM RLE_ENTRY
#define RLE_HORIZON_PARAM RLE_ENTRY
#define RLE_LEARNING_PARAM RLE_ENTRY
#define RLE_LEARNING_LOOP_PARAM RLE_ENTRY
#define RLE_FIELD_COLOR_PARAM RLE_ENTRY
#define RLE_FIELD_BOUNDARY_PARAM RLE_ENTRY
#include "rle_vision/params/landmark_params.def"
#undef RLE_ENTRY
  yaml << "low_priority: true  # ROS: run the landmark and edge workers at nice 19 / SCHED_IDLE\n";
  return yaml.str();
}

LandmarkOptions parseLandmarkParams(const std::string& text, const std::string& origin) {
  LandmarkOptions o;
  const YAML::Node root = parseChecked(text, origin);
  if (!root || root.IsNull()) return o;
#define RLE_EDGE_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.member, min, max);
#define RLE_OBJECTS_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.objects.member, min, max);
#define RLE_HOUGH_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.hough.member, min, max);
#define RLE_HORIZON_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.horizon.member, min, max);
#include "rle_vision/params/landmark_params.def"
  const std::string problem = validateLandmarkOptions(o);
  if (!problem.empty()) yaml_reader::fail(origin, root, problem);
  return o;
}

LandmarkOptions loadLandmarkParams(const std::string& path) { return parseLandmarkParams(yaml_reader::readFile(path), path); }

LearningOptions parseLearningParams(const std::string& text, const std::string& origin) {
  LearningOptions o;
  const YAML::Node root = parseChecked(text, origin);
  if (!root || root.IsNull()) return o;
#define RLE_LEARNING_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.member, min, max);
#include "rle_vision/params/landmark_params.def"
  const std::string problem = validateLearningOptions(o);
  if (!problem.empty()) yaml_reader::fail(origin, root, problem);
  return o;
}

LearningOptions loadLearningParams(const std::string& path) { return parseLearningParams(yaml_reader::readFile(path), path); }

LearningLoopOptions parseLearningLoopParams(const std::string& text, const std::string& origin) {
  LearningLoopOptions o;
  const YAML::Node root = parseChecked(text, origin);
  if (!root || root.IsNull()) return o;
#define RLE_LEARNING_LOOP_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.member, min, max);
#include "rle_vision/params/landmark_params.def"
  const std::string problem = validateLearningLoopOptions(o);
  if (!problem.empty()) yaml_reader::fail(origin, root, problem);
  return o;
}

LearningLoopOptions loadLearningLoopParams(const std::string& path) {
  return parseLearningLoopParams(yaml_reader::readFile(path), path);
}

FieldOptions parseFieldParams(const std::string& text, const std::string& origin) {
  FieldOptions o;
  const YAML::Node root = parseChecked(text, origin);
  if (!root || root.IsNull()) return o;
#define RLE_FIELD_COLOR_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.colour.member, min, max);
#define RLE_FIELD_BOUNDARY_PARAM(key, member, type, default_value, min, max, description) read(origin, root, #key, &o.boundary.member, min, max);
#include "rle_vision/params/landmark_params.def"
  const std::string problem = validateFieldOptions(o);
  if (!problem.empty()) yaml_reader::fail(origin, root, problem);
  return o;
}

FieldOptions loadFieldParams(const std::string& path) { return parseFieldParams(yaml_reader::readFile(path), path); }

}  // namespace rle_vision
