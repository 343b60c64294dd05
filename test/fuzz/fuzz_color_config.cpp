// libFuzzer target: the colour-file parsers (colors.yaml and CMVision colors.txt) on arbitrary
// text. Bad files must end in a ConfigError, never a crash; good ones must build a table.
#include <cstddef>
#include <cstdint>
#include <string>

#include "rle_vision/color/color_table.h"
#include "rle_vision/io/color_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (int format = 0; format < 2; ++format) {
    try {
      const std::vector<rle_vision::ColorClass> classes = format == 0
                                                              ? rle_vision::parseColorClassesYaml(text, "fuzz.yaml")
                                                              : rle_vision::parseCmvisionColors(text, "fuzz.txt");
      const rle_vision::ColorTable table(classes);  // a parsed file is a usable table
      (void)table;
    } catch (const rle_vision::ConfigError&) {
    }
  }
  return 0;
}
