// Reading and writing colour classes. Every error names the file, the line and the reason,
// e.g. "config/colors.yaml:12: 'min' must be a list of 3 integers 0..255".
#pragma once

#include <string>
#include <vector>

#include "rle_vision/color/color_class.h"
#include "rle_vision/io/config_error.h"

namespace rle_vision {

// colors.yaml (see config/colors.yaml) or a CMVision colors.txt ([Colors] and [Thresholds]
// sections; the format is chosen by content, not by name). Throws ConfigError.
std::vector<ColorClass> loadColorClasses(const std::string& path);
std::vector<ColorClass> parseColorClassesYaml(const std::string& text, const std::string& origin);
std::vector<ColorClass> parseCmvisionColors(const std::string& text, const std::string& origin);

// Writes classes as colors.yaml text (loadColorClasses reads it back unchanged).
std::string colorClassesToYaml(const std::vector<ColorClass>& classes);

// CMVision's colors.txt ([Colors] and [Thresholds], no comments inside the sections: its
// parser ends a section at a comment) for YUV classes. Throws std::invalid_argument for
// another space.
std::string cmvisionColorsText(const std::vector<ColorClass>& classes);

// `classes` with `c` in place of the class of the same name (which keeps its verifier), or
// with `c` appended (last: lowest priority): what saving a calibrated class into a file does.
std::vector<ColorClass> mergeColorClass(std::vector<ColorClass> classes, const ColorClass& c);

// Saves a calibrated class into a colors.yaml and/or a CMVision colors.txt (an empty path:
// not that one): a class of the same name is replaced (keeping its verifier), the others are
// kept (comments are not), a missing file is created. Both texts are made before either file
// is written, so a class one file cannot take (HSV into colors.txt) leaves both as they were.
// Throws ConfigError for a broken existing file, std::invalid_argument otherwise.
void saveColorClassInto(const ColorClass& c, const std::string& yaml_path, const std::string& cmvision_path);

}  // namespace rle_vision
