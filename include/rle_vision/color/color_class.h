// Colour classes: boxes in a colour space, as CMVision uses them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rle_vision {

// At most this many classes fit in one pass of the per-channel bit tables.
constexpr int kMaxColorClasses = 32;

// The class the field stage's colour is published as (the floor's colour, learned).
constexpr const char* kFieldClassName = "field";
// The tracker's hidden class just before a class with a verifier: the floor's colour grown by
// the verifier's floor guard scale (verify/candidate_screen.h, withFloorGuard). No blob of it.
constexpr const char* kFloorGuardClassName = "floor_guard";

enum class ColorSpace : uint8_t {
  YUV = 0,  // OpenCV COLOR_BGR2YUV on RGB input; the camera's own YUV on yuv422 input
  RGB = 1,
  HSV = 2,  // OpenCV 8-bit HSV: H in 0..179, S and V in 0..255
};
constexpr int kNumColorSpaces = 3;

const char* toString(ColorSpace space);
// Case-insensitive; an empty string means YUV (the default). Returns false on unknown names.
bool parseColorSpace(const std::string& text, ColorSpace* space);

using Channels = std::array<uint8_t, 3>;

struct ColorClass {
  std::string name;
  ColorSpace space = ColorSpace::YUV;
  Channels min{{0, 0, 0}};  // inclusive; min > max on a channel means the range wraps 255 -> 0
  Channels max{{255, 255, 255}};
  Channels display_rgb{{255, 255, 255}};
  uint32_t min_area_px = 1;
  std::string source = "config";  // "config" or "learned"
  // A learned verifier (verify/blob_verifier.h) judges this class's blobs: its model file as
  // written in the colours file (relative to that file's folder, or absolute; written back as
  // it is), the file to load (verifier_file resolved when the colours are read), and the lowest
  // score a published blob may have. Empty: colour alone decides.
  std::string verifier_file;
  std::string verifier_path;
  double min_score = 0.5;

  // True when the channel value lies in [min, max] (or in the wrapped range).
  bool channelContains(int channel, uint8_t value) const {
    // Unsigned modular distance: handles the wrapped case min > max without a branch.
    return static_cast<uint8_t>(value - min[channel]) <=
           static_cast<uint8_t>(max[channel] - min[channel]);
  }
  bool contains(const Channels& pixel) const {
    return channelContains(0, pixel[0]) && channelContains(1, pixel[1]) &&
           channelContains(2, pixel[2]);
  }
  // True when the class only constrains brightness, so it can be evaluated on mono8 images.
  bool ignoresChroma() const;
  // The brightness range used on mono8 images (only meaningful when ignoresChroma()).
  void brightnessRange(uint8_t* lo, uint8_t* hi) const;
};

// Checks a class set: 1..32 classes, unique non-empty names. Returns an empty string when
// valid, otherwise the reason.
std::string validateColorClasses(const std::vector<ColorClass>& classes);

// True for a name colors.yaml and CMVision's colors.txt both take: letters, digits, '_', '-'.
bool isPortableClassName(const std::string& name);

}  // namespace rle_vision
