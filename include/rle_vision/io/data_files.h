// Where the package's own data files (config/colors.yaml, scene files) are for a program of
// the package: installed (catkin or plain CMake), in a build tree, or named by the user.
#pragma once

#include <string>

namespace rle_vision {

// The path of `relative` (e.g. "config/colors.yaml") in the first of: $RLE_VISION_DATA_DIR;
// the share/rle_vision folder of the prefix the running executable is installed in
// (<prefix>/bin or <prefix>/lib/rle_vision); the source tree it was built from. "" when none
// holds it.
std::string packageDataFile(const std::string& relative);

}  // namespace rle_vision
