#include "rle_vision/color/color_class.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace rle_vision {

const char* toString(ColorSpace space) {
  switch (space) {
    case ColorSpace::YUV: return "YUV";
    case ColorSpace::RGB: return "RGB";
    case ColorSpace::HSV: return "HSV";
  }
  return "?";
}

bool parseColorSpace(const std::string& text, ColorSpace* space) {
  std::string upper(text);
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (upper.empty() || upper == "YUV") {
    *space = ColorSpace::YUV;
  } else if (upper == "RGB") {
    *space = ColorSpace::RGB;
  } else if (upper == "HSV") {
    *space = ColorSpace::HSV;
  } else {
    return false;
  }
  return true;
}

namespace {
bool isFullRange(const ColorClass& c, int channel) {
  return c.min[channel] == 0 && c.max[channel] == 255;
}
}  // namespace

bool ColorClass::ignoresChroma() const {
  switch (space) {
    case ColorSpace::YUV: return isFullRange(*this, 1) && isFullRange(*this, 2);
    case ColorSpace::HSV: return min[0] == 0 && max[0] >= 179 && isFullRange(*this, 1);  // hue is 0..179
    case ColorSpace::RGB:  // a gray pixel has r = g = b, so equal ranges test brightness only
      return min[0] == min[1] && min[1] == min[2] && max[0] == max[1] && max[1] == max[2];
  }
  return false;
}

void ColorClass::brightnessRange(uint8_t* lo, uint8_t* hi) const {
  const int channel = space == ColorSpace::HSV ? 2 : 0;
  *lo = min[channel];
  *hi = max[channel];
}

std::string validateColorClasses(const std::vector<ColorClass>& classes) {
  if (classes.empty()) return "no colour classes defined";
  if (classes.size() > static_cast<size_t>(kMaxColorClasses)) {
    return std::to_string(classes.size()) + " colour classes defined, at most " +
           std::to_string(kMaxColorClasses) + " are supported";
  }
  std::set<std::string> names;
  for (const ColorClass& c : classes) {
    if (c.name.empty()) return "a colour class has an empty name";
    if (!names.insert(c.name).second) return "colour class name '" + c.name + "' is used twice";
    if (!(c.min_score >= 0.0 && c.min_score <= 1.0)) {
      return "colour class '" + c.name + "': min_score must be a score in 0..1, got " + std::to_string(c.min_score);
    }
    static const char* kChannelNames[3][3] = {{"Y", "U", "V"}, {"R", "G", "B"}, {"H", "S", "V"}};
    for (int ch = 0; ch < 3; ++ch) {
      const bool hue = c.space == ColorSpace::HSV && ch == 0;
      const std::string channel = std::string(toString(c.space)) + " " + kChannelNames[static_cast<int>(c.space)][ch];
      if (c.min[ch] > c.max[ch] && !hue) {
        return "colour class '" + c.name + "': min " + std::to_string(c.min[ch]) + " > max " +
               std::to_string(c.max[ch]) + " on " + channel + " (only the HSV hue may wrap around)";
      }
      if (hue && (c.min[ch] > 179 || c.max[ch] > 179)) {
        return "colour class '" + c.name + "': HSV hue bounds must be 0..179 (OpenCV's 8-bit hue), got " +
               std::to_string(c.min[ch]) + ".." + std::to_string(c.max[ch]);
      }
    }
  }
  return "";
}

bool isPortableClassName(const std::string& name) {
  static const char* kAllowed = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-";
  return !name.empty() && name.find_first_not_of(kAllowed) == std::string::npos;
}

}  // namespace rle_vision
