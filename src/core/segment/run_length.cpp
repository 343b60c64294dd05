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
// With a flip filter, the row's stretches (background included) wait in a queue of three: a
// middle one of at most max_flip_px pixels between two of one label joins them, so a noisy
// pixel neither cuts a run nor makes a speck.
class RowRuns {
 public:
  RowRuns(const uint8_t* labels, int y, int max_flip_px, std::vector<Run>* runs)
      : labels_(labels), y_(y), max_flip_px_(max_flip_px), runs_(runs), label_(labels[0]) {}

  // A run of another label starts at x.
  void startAt(int x) {
    close(x);
    start_ = x;
    label_ = labels_[x];
  }
  // The row ends at `width`.
  void finish(int width) {
    close(width);
    for (int k = 0; k < pending_count_; ++k) emit(pending_[k]);
  }

 private:
  struct Stretch {
    int x0, x1;
    uint8_t label;
  };

  void close(int end) {
    const Stretch stretch{start_, end - 1, label_};
    if (max_flip_px_ == 0) {
      emit(stretch);
      return;
    }
    pending_[pending_count_++] = stretch;
    if (pending_count_ < 3) return;
    // Neighbouring stretches always differ in label, so the middle one is a flip exactly when
    // the outer two agree.
    if (pending_[1].x1 - pending_[1].x0 < max_flip_px_ && pending_[0].label == pending_[2].label) {
      pending_[0].x1 = pending_[2].x1;
      pending_count_ = 1;
    } else {
      emit(pending_[0]);
      pending_[0] = pending_[1];
      pending_[1] = pending_[2];
      pending_count_ = 2;
    }
  }
  void emit(const Stretch& s) {
    if (s.label != 0) runs_->push_back(Run{s.x0, s.x1, y_, static_cast<int32_t>(runs_->size()), s.label});
  }

  const uint8_t* labels_;
  int y_;
  int max_flip_px_;
  std::vector<Run>* runs_;
  int start_ = 0;
  uint8_t label_;
  Stretch pending_[3];
  int pending_count_ = 0;
};

// From x on, 8 labels at a time: the XOR of a word with the word one label earlier is
// non-zero exactly in the bytes where a new run starts. Returns where it stopped.
int scanWords(const uint8_t* labels, int width, int x, RowRuns* row) {
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
    for (; changed != 0; changed &= changed - 1) row->startAt(x + (__builtin_ctzll(changed) >> 3));
  }
  return x;
}

#ifdef RLE_VISION_HAVE_AVX2_RLE
bool avx2Available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

// The same with 32 labels at a time.
__attribute__((target("avx2"))) int scanAvx2(const uint8_t* labels, int width, int x, RowRuns* row) {
  for (; x + 32 <= width; x += 32) {
    const __m256i here = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(labels + x));
    const __m256i before = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(labels + x - 1));
    uint32_t changed = ~static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(here, before)));
    for (; changed != 0; changed &= changed - 1) row->startAt(x + __builtin_ctz(changed));
  }
  return x;
}
#endif

}  // namespace

void appendRowRuns(const uint8_t* labels, int width, int y, std::vector<Run>* runs, int max_flip_px) {
  if (width <= 0) return;
  RowRuns row(labels, y, std::max(max_flip_px, 0), runs);
  int x = 1;
#ifdef RLE_VISION_HAVE_AVX2_RLE
  if (avx2Available()) x = scanAvx2(labels, width, x, &row);
#endif
  x = scanWords(labels, width, x, &row);
  for (; x < width; ++x) {
    if (labels[x] != labels[x - 1]) row.startAt(x);
  }
  row.finish(width);
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
