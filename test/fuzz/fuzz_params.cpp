// libFuzzer target: the landmark/learning parameter and scene file parsers on arbitrary text.
#include <cstddef>
#include <cstdint>
#include <string>

#include "rle_vision/io/landmark_params_file.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    rle_vision::parseLandmarkParams(text, "fuzz.yaml");
  } catch (const rle_vision::ConfigError&) {
  }
  try {
    rle_vision::parseLearningParams(text, "fuzz.yaml");
  } catch (const rle_vision::ConfigError&) {
  }
  try {
    const rle_vision::SceneConfig scene = rle_vision::parseSceneConfig(text, "fuzz.yaml");
    // A scene that parses is valid: the simulator accepts it (rendering is not fuzzed: slow).
    const rle_vision::SceneSimulator simulator(scene);
    (void)simulator;
  } catch (const rle_vision::ConfigError&) {
  }
  return 0;
}
