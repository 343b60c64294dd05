#include "rle_vision/run_length.h"

#include <cstring>

#include "simd_dispatch.h"

namespace rle_vision {

RLE_VISION_HOT
void appendRowRuns(const uint8_t* labels, int width, int y, std::vector<Run>* runs) {
  constexpr uint64_t kOnes = 0x0101010101010101ull;
  int x = 0;
  while (x < width) {
    const uint8_t label = labels[x];
    const int start = x++;
    // Skip 8 equal labels at a time: long runs (and background) cost one compare per word.
    const uint64_t pattern = kOnes * label;
    while (x + 8 <= width) {
      uint64_t word;
      std::memcpy(&word, labels + x, sizeof(word));
      if (word != pattern) break;
      x += 8;
    }
    while (x < width && labels[x] == label) ++x;
    if (label != 0) {
      const int32_t index = static_cast<int32_t>(runs->size());
      runs->push_back(Run{start, x - 1, y, index, label});
    }
  }
}

void encodeLabelRows(const uint8_t* const* rows, int width, int height, std::vector<Run>* runs,
                     std::vector<int32_t>* row_starts) {
  runs->clear();
  row_starts->resize(static_cast<size_t>(height) + 1);
  for (int y = 0; y < height; ++y) {
    (*row_starts)[y] = static_cast<int32_t>(runs->size());
    appendRowRuns(rows[y], width, y, runs);
  }
  (*row_starts)[height] = static_cast<int32_t>(runs->size());
}

}  // namespace rle_vision
