#include "rle_vision/segment/run_length.h"

#include <algorithm>
#include <cstring>

#include "common/simd_dispatch.h"
#include "segment/flip_filter_words.h"
#include "segment/row_encoders.h"

namespace rle_vision {
namespace {

using row_encoding::FlipFilterRow;
using row_encoding::PlainRow;
using row_encoding::RowBuffer;

// Runs are found from their ends: a run ends where a label differs from the one before it.
// Finding those places many labels at a time costs one step per run, not one branch per pixel,
// which matters on noisy frames (thousands of short runs) and costs little on clean ones.

// From x on, 8 labels at a time: the XOR of a word with the word one label earlier is
// non-zero exactly in the bytes where a new run starts. Returns where it stopped.
template <typename Row>
int scanWords(const uint8_t* labels, int width, int x, Row* row) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "byte i of a loaded word is label x + i");
  constexpr uint64_t kLowBits = 0x0101010101010101ull;
  for (; x + 8 <= width; x += 8) {
    uint64_t here, before;
    std::memcpy(&here, labels + x, sizeof(here));
    std::memcpy(&before, labels + x - 1, sizeof(before));
    uint64_t changed = here ^ before;
    if (changed == 0) continue;
    // One bit per changed byte, its lowest (little-endian: byte i is bits 8i..8i+7).
    changed |= changed >> 4;
    changed |= changed >> 2;
    changed |= changed >> 1;
    changed &= kLowBits;
    for (; changed != 0; changed &= changed - 1) row->changeAt(x + (__builtin_ctzll(changed) >> 3));
  }
  return x;
}

#ifdef RLE_VISION_AVX2_KERNELS
// The same with 32 labels at a time. The row is worked on as a local copy, so its state stays
// in registers.
template <typename Row>
__attribute__((target("avx2"))) int scanAvx2(const uint8_t* labels, int width, int x, Row* row_in) {
  Row row = *row_in;
  for (; x + 32 <= width; x += 32) {
    const __m256i here = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(labels + x));
    const __m256i before = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(labels + x - 1));
    uint32_t changed = ~static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(here, before)));
    for (; changed != 0; changed &= changed - 1) row.changeAt(x + __builtin_ctz(changed));
  }
  *row_in = row;
  return x;
}
#endif

// Calls row->changeAt(x) for every x where a new stretch starts, left to right; returns the
// number of runs the row wrote.
template <typename Row>
int32_t encodeRow(const uint8_t* labels, int width, Row* row) {
  int x = 1;
#ifdef RLE_VISION_AVX2_KERNELS
  if (cpuHasAvx2()) x = scanAvx2(labels, width, x, row);
#endif
  x = scanWords(labels, width, x, row);
  for (; x < width; ++x) {
    if (labels[x] != labels[x - 1]) row->changeAt(x);
  }
  return row->finish(width);
}

}  // namespace

void RowRunEncoder::append(const uint8_t* labels, int width, int y, std::vector<Run>* runs, int max_flip_px) {
  if (width <= 0) return;
  // Each of the row's at most `width` stretches may be written before it is counted.
  if (row_buffer_.size() < static_cast<size_t>(width) + 1) row_buffer_.resize(static_cast<size_t>(width) + 1);
  const RowBuffer buffer(row_buffer_.data(), y, static_cast<int32_t>(runs->size()));
  int32_t count = 0;
  if (max_flip_px <= 0) {
    PlainRow row(labels, buffer);
    count = encodeRow(labels, width, &row);
  } else if (noisy_row_before_ && max_flip_px <= kMaxWordFlipPx && flipFilterWordsAvailable()) {
    int stretch_starts = 0;
    count = encodeFlipFilterRowWords(labels, width, max_flip_px, buffer, &word_buffers_, &stretch_starts);
    noisy_row_before_ = isNoisyRow(stretch_starts, width);
  } else {
    // Rows are noisy in patches: a row's encoding is chosen by the row before it.
    FlipFilterRow row(labels, max_flip_px, buffer);
    count = encodeRow(labels, width, &row);
    noisy_row_before_ = isNoisyRow(row.stretchStarts(), width);
  }
  runs->insert(runs->end(), row_buffer_.begin(), row_buffer_.begin() + count);
}

void appendRowRuns(const uint8_t* labels, int width, int y, std::vector<Run>* runs, int max_flip_px) {
  static thread_local RowRunEncoder encoder;
  encoder.append(labels, width, y, runs, max_flip_px);
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
