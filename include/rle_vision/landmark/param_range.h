// Range checks of the parameters in landmark_params.def, shared by the core's option checks.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>

namespace rle_vision {

// "" when `value` is a finite number in [min, max]; otherwise the problem, naming the
// parameter by its ROS / file key. Booleans are always in range.
template <typename T>
std::string outOfRange(const char* key, T value, double min, double max) {
  if (std::is_same<T, bool>::value) return "";
  const double v = static_cast<double>(value);
  if (std::isfinite(v) && v >= min && v <= max) return "";
  std::ostringstream text;
  text << key << " = " << v << " is outside [" << min << ", " << max << "]";
  return text.str();
}

}  // namespace rle_vision
