// The randomized Hough's sparse accumulator for one edge object (private to the core):
// random pixel pairs drawn uniformly from the object's runs vote for their lines in the
// paper's (theta, intercept) space.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rle_vision/landmark/hough_options.h"
#include "rle_vision/segment/run_length.h"

namespace rle_vision {
namespace hough {

// A voted cell: key = theta bin * intercept bins + intercept bin.
struct Cell {
  uint32_t key;
  uint32_t votes;
};

// The line a cell stands for (its bin centres): a x + b y + c = 0, (a, b) = (-sin, cos) theta.
struct CellLine {
  double a, b, c, theta;
};

class Accumulator {
 public:
  // Draws `samples` pairs from the runs (a second pixel too close to the first is redrawn)
  // and counts their votes. Afterwards cells() holds the voted cells ordered by theta bin
  // (within a bin, in the order first voted for: deterministic) and cellLines() their lines.
  void vote(const Run* runs, int run_count, uint64_t samples, uint64_t seed, int width, int height,
            const HoughOptions& options);

  const std::vector<Cell>& cells() const { return cells_; }
  const std::vector<CellLine>& cellLines() const { return cell_lines_; }
  int thetaBins() const { return theta_bins_; }
  int thetaBinOf(size_t cell) const { return static_cast<int>(cells_[cell].key / intercept_bins_); }
  // The cells of theta bin b are [binBegin(b), binEnd(b)).
  int binBegin(int bin) const { return bucket_start_[bin]; }
  int binEnd(int bin) const { return bucket_start_[bin + 1]; }

 private:
  struct PixelXY {
    int16_t x, y;
  };
  void sizeAccumulator(uint64_t samples, int width, int height, const HoughOptions& options);
  void fillPixelTable(const Run* runs, int run_count);
  void drawPairs(uint64_t samples, uint64_t seed, const HoughOptions& options);
  void countVotes();
  void computeCellLines(const HoughOptions& options);

  std::vector<PixelXY> pixels_;
  size_t capacity_ = 0;
  std::vector<Cell> table_;          // open addressing; slots beyond capacity_ unused
  std::vector<uint32_t> occupied_;   // slots of table_ in use
  std::vector<uint32_t> keys_;       // the cell each pair of a round votes for
  std::vector<Cell> cells_;
  std::vector<int> bucket_start_, fill_;
  std::vector<CellLine> cell_lines_;
  std::vector<double> bin_theta_, bin_normal_x_, bin_normal_y_;  // per theta bin
  double bins_for_deg_ = 0;                                       // the bin size they are for
  int theta_bins_ = 0, intercept_bins_ = 0;
  double alpha_ = 0;
};

}  // namespace hough
}  // namespace rle_vision
