#include "rle_vision/color/color_table.h"

#include <atomic>
#include <cstring>
#include <stdexcept>

#include "rle_vision/color/color_convert.h"

namespace rle_vision {

namespace {
std::atomic<uint64_t> next_serial{1};
}  // namespace

ColorTable::ColorTable(std::vector<ColorClass> classes)
    : classes_(std::move(classes)), serial_(next_serial.fetch_add(1)) {
  const std::string problem = validateColorClasses(classes_);
  if (!problem.empty()) throw std::invalid_argument(problem);
  std::memset(tables_, 0, sizeof(tables_));
  std::memset(space_bits_, 0, sizeof(space_bits_));
  std::memset(mono_, 0, sizeof(mono_));
  for (size_t k = 0; k < classes_.size(); ++k) {
    const ColorClass& c = classes_[k];
    const uint32_t bit = 1u << k;
    const int s = static_cast<int>(c.space);
    space_bits_[s] |= bit;
    for (int channel = 0; channel < 3; ++channel) {
      for (int value = 0; value < 256; ++value) {
        if (c.channelContains(channel, static_cast<uint8_t>(value))) tables_[s][channel][value] |= bit;
      }
    }
    if (c.ignoresChroma()) {
      uint8_t lo = 0, hi = 0;
      c.brightnessRange(&lo, &hi);
      for (int value = 0; value < 256; ++value) {
        if (static_cast<uint8_t>(value - lo) <= static_cast<uint8_t>(hi - lo)) mono_[value] |= bit;
      }
    } else {
      chroma_bits_ |= bit;
    }
  }
}

int ColorTable::indexOf(const std::string& name) const {
  for (size_t k = 0; k < classes_.size(); ++k) {
    if (classes_[k].name == name) return static_cast<int>(k);
  }
  return -1;
}

int ColorTable::classifyBgr(uint8_t b, uint8_t g, uint8_t r) const {
  uint32_t m = 0;
  for (int s = 0; s < kNumColorSpaces; ++s) {
    if (space_bits_[s] == 0) continue;
    m |= mask(static_cast<ColorSpace>(s), convertBgrPixel(b, g, r, static_cast<ColorSpace>(s)));
  }
  return firstClassLabel(m);
}

}  // namespace rle_vision
