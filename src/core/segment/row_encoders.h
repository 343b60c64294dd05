// The row encoders behind appendRowRuns: where a row's runs are written, and the state a row
// keeps from one stretch start to the next, plain or with the flip filter.
#pragma once

#include <cstdint>

#include "rle_vision/segment/run_length.h"

namespace rle_vision {
namespace row_encoding {

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
    ++stretch_starts_;
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
  // The row's stretch starts so far, the first pixel included.
  int stretchStarts() const { return stretch_starts_; }

 private:
  const uint8_t* labels_;
  int max_flip_px_;
  int stretch_starts_ = 1;
  RowBuffer buffer_;
  int a_start_ = 0, b_start_ = 0;
  uint8_t a_label_, b_label_ = 0;
  bool has_b_ = false;
};

}  // namespace row_encoding
}  // namespace rle_vision
