#include "rle_vision/segment/run_length.h"

#include <algorithm>
#include <cstring>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(RLE_VISION_NO_MULTIVERSION)
#define RLE_VISION_HAVE_AVX2_RLE 1
#include <immintrin.h>
#endif

namespace rle_vision {
namespace {

// Runs are found from their ends: a run ends where a label differs from the one before it.
// Finding those places many labels at a time costs one step per run, not one branch per pixel,
// which matters on noisy frames (thousands of short runs) and costs little on clean ones.
//
// On a noisy row whether a stretch is kept (labelled, not background) or, with a flip filter,
// merged is a coin toss, so the row encoders below avoid a branch on it: every stretch is
// written to the row's buffer and the count moves on only for one kept, and the flip filter's
// state moves by conditional assignments (the compiler may still branch on the merge).
class RowBuffer {
 public:
  RowBuffer(Run* out, int y, int32_t first_index) : out_(out), y_(y), first_index_(first_index) {}

  void add(int x0, int x1, uint8_t label, bool keep) {
    out_[count_] = Run{x0, x1, y_, first_index_ + count_, label};
    count_ += static_cast<int32_t>(keep && label != 0);
  }
  int32_t count() const { return count_; }

 private:
  Run* out_;
  int y_;
  int32_t first_index_;
  int32_t count_ = 0;
};

// Every stretch of one label is a run (background dropped).
class PlainRow {
 public:
  PlainRow(const uint8_t* labels, RowBuffer buffer) : labels_(labels), buffer_(buffer), label_(labels[0]) {}

  // A stretch of another label starts at x.
  void changeAt(int x) {
    buffer_.add(start_, x - 1, label_, true);
    start_ = x;
    label_ = labels_[x];
  }
  // The row ends at `width`.
  int32_t finish(int width) {
    buffer_.add(start_, width - 1, label_, true);
    return buffer_.count();
  }

 private:
  const uint8_t* labels_;
  RowBuffer buffer_;
  int start_ = 0;
  uint8_t label_;
};

// The flip filter: a stretch B of at most max_flip_px pixels between a stretch A and a stretch
// C of A's label joins them. Stretches are told apart by their starts; B's fate is known as soon
// as C starts (its length and C's label), so the row keeps only A, and B once it has begun.
class FlipFilterRow {
 public:
  FlipFilterRow(const uint8_t* labels, int max_flip_px, RowBuffer buffer)
      : labels_(labels), max_flip_px_(max_flip_px), buffer_(buffer), a_label_(labels[0]) {}

  void changeAt(int x) {
    const uint8_t label = labels_[x];
    const bool merge = has_b_ && x - b_start_ <= max_flip_px_ && label == a_label_;
    const bool shift = has_b_ && !merge;  // A is done: B becomes A, the new stretch B
    buffer_.add(a_start_, b_start_ - 1, a_label_, shift);
    a_start_ = shift ? b_start_ : a_start_;
    a_label_ = shift ? b_label_ : a_label_;
    b_start_ = merge ? b_start_ : x;
    b_label_ = merge ? b_label_ : label;
    has_b_ = !merge;
  }
  int32_t finish(int width) {
    if (has_b_) {
      buffer_.add(a_start_, b_start_ - 1, a_label_, true);
      buffer_.add(b_start_, width - 1, b_label_, true);
    } else {
      buffer_.add(a_start_, width - 1, a_label_, true);
    }
    return buffer_.count();
  }

 private:
  const uint8_t* labels_;
  int max_flip_px_;
  RowBuffer buffer_;
  int a_start_ = 0, b_start_ = 0;
  uint8_t a_label_, b_label_ = 0;
  bool has_b_ = false;
};

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

#ifdef RLE_VISION_HAVE_AVX2_RLE
bool avx2Available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

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
int32_t encodeRow(const uint8_t* labels, int width, Row row) {
  int x = 1;
#ifdef RLE_VISION_HAVE_AVX2_RLE
  if (avx2Available()) x = scanAvx2(labels, width, x, &row);
#endif
  x = scanWords(labels, width, x, &row);
  for (; x < width; ++x) {
    if (labels[x] != labels[x - 1]) row.changeAt(x);
  }
  return row.finish(width);
}

}  // namespace

void appendRowRuns(const uint8_t* labels, int width, int y, std::vector<Run>* runs, int max_flip_px) {
  if (width <= 0) return;
  // Each of the row's at most `width` stretches may be written before it is counted.
  static thread_local std::vector<Run> row_buffer;
  if (row_buffer.size() < static_cast<size_t>(width) + 1) row_buffer.resize(static_cast<size_t>(width) + 1);
  const RowBuffer buffer(row_buffer.data(), y, static_cast<int32_t>(runs->size()));
  const int32_t count = max_flip_px > 0 ? encodeRow(labels, width, FlipFilterRow(labels, max_flip_px, buffer))
                                        : encodeRow(labels, width, PlainRow(labels, buffer));
  runs->insert(runs->end(), row_buffer.begin(), row_buffer.begin() + count);
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
