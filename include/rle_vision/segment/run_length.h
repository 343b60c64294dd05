// Run-length encoding of labelled rows.
#pragma once

#include <cstdint>
#include <vector>

namespace rle_vision {

// A horizontal run of equally labelled pixels.
struct Run {
  int32_t x0;      // first pixel, inclusive
  int32_t x1;      // last pixel, inclusive
  int32_t y;       // row
  int32_t parent;  // union-find parent: index into the run list
  uint8_t label;   // 1 + colour class index (label 0, background, is never stored)

  int32_t length() const { return x1 - x0 + 1; }
};

// Appends the runs of one row of labels (label 0 is background and produces no run).
// Runs are appended left to right with parent = their own index. With max_flip_px > 0, a
// stretch of at most that many pixels of one label between two stretches of another one label
// (background included) takes their label, left to right: a noisy pixel neither cuts a run nor
// makes a speck. The first and last stretch of a row are never relabelled (they have one
// neighbour), though the first may grow by the flips after it.
void appendRowRuns(const uint8_t* labels, int width, int y, std::vector<Run>* runs, int max_flip_px = 0);

// The flip filter's buffers for noisy rows (the labels with room around them, rows of bits).
struct FlipFilterWordBuffers {
  std::vector<uint8_t> padded_labels;
  std::vector<uint64_t> bits;
};

// appendRowRuns with its buffers kept from row to row (use one per thread; appendRowRuns keeps
// one per thread). With the flip filter (max_flip_px up to 8, on a CPU with AVX2) a row after a
// noisy row is worked on 64 pixels at a time, others stretch by stretch; the runs are the same
// either way.
class RowRunEncoder {
 public:
  void append(const uint8_t* labels, int width, int y, std::vector<Run>* runs, int max_flip_px = 0);

 private:
  std::vector<Run> row_buffer_;
  FlipFilterWordBuffers word_buffers_;
  bool noisy_row_before_ = false;
};

// Run-length encodes a whole CV_8UC1 label image given as rows: fills `runs` (row-major order)
// and `row_starts` (size rows + 1; the runs of row y are [row_starts[y], row_starts[y + 1])).
void encodeLabelRows(const uint8_t* const* rows, int width, int height, std::vector<Run>* runs,
                     std::vector<int32_t>* row_starts);

}  // namespace rle_vision
