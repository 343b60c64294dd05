// An immutable, validated set of colour classes and its CMVision-style lookup tables.
// Built off the frame path and shared by pointer, so a new set can be swapped in while
// frames are being segmented with the old one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rle_vision/color/color_class.h"

namespace rle_vision {

class ColorTable {
 public:
  // Throws std::invalid_argument (with the reason) when the classes are invalid.
  explicit ColorTable(std::vector<ColorClass> classes);

  const std::vector<ColorClass>& classes() const { return classes_; }
  // Unique per constructed table in this process: lets caches tell tables apart even when a
  // new table reuses a freed one's address.
  uint64_t serial() const { return serial_; }
  int size() const { return static_cast<int>(classes_.size()); }
  // Index of the class with this name, or -1.
  int indexOf(const std::string& name) const;

  // CMVision's trick: three 256-entry per-channel bit tables per colour space; bit k of the
  // AND of the three entries is set when class k (a class of that space) contains the pixel.
  uint32_t mask(ColorSpace space, const Channels& pixel) const {
    const auto& t = tables_[static_cast<int>(space)];
    return t[0][pixel[0]] & t[1][pixel[1]] & t[2][pixel[2]];
  }
  // Bit k set when class k is in `space`.
  uint32_t classesIn(ColorSpace space) const { return space_bits_[static_cast<int>(space)]; }
  // Bit k set when class k matches this gray level on a mono8 image (classes that constrain
  // chroma never match mono8 images).
  uint32_t monoMask(uint8_t gray) const { return mono_[gray]; }
  // Bit k set when class k constrains chroma and is therefore skipped on mono8 images.
  uint32_t chromaClasses() const { return chroma_bits_; }

  // Reference (scalar) classification of one BGR pixel: 1 + index of the first matching
  // class, or 0 when no class matches.
  int classifyBgr(uint8_t b, uint8_t g, uint8_t r) const;

 private:
  std::vector<ColorClass> classes_;
  uint64_t serial_;
  uint32_t tables_[kNumColorSpaces][3][256];
  uint32_t space_bits_[kNumColorSpaces];
  uint32_t mono_[256];
  uint32_t chroma_bits_ = 0;
};

// 1 + index of the lowest set bit, or 0 for an empty mask (the label of the winning class).
inline int firstClassLabel(uint32_t mask) { return mask == 0 ? 0 : __builtin_ctz(mask) + 1; }

}  // namespace rle_vision
