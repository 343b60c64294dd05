// Region evidence for the horizon (private to the core): the frame's colours on a coarse grid
// of cells, and for any line the colour statistics of the two sides it splits the frame into,
// in O(grid width) through prefix sums of the colour moments. A horizon splits the frame into
// two regions that each look like one colour distribution (sky, ground): the search finds the
// lines that maximise the two-Gaussian log-likelihood gain of that split.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {
namespace horizon {

// A line n . p = rho with n = (-sin a, cos a) (pointing down, towards the ground side), a in
// (-90, 90] deg; side 0, {n . p < rho}, is the sky side.
struct SplitLine {
  double angle_deg = 0;
  double nx = 0, ny = 1, rho = 0;
  static SplitLine fromAngleDistance(double angle_deg, double centre_distance, int width, int height);
  static SplitLine fromImageLine(const ImageLine& line);
  double centreDistance(int width, int height) const { return rho - nx * 0.5 * width - ny * 0.5 * height; }
  double signedDistance(double x, double y) const { return nx * x + ny * y - rho; }  // < 0: sky side
  ImageLine imageLine() const { return lineFromHomogeneous(nx, ny, -rho); }
};

constexpr int kMoments = 10;  // 1, c0, c1, c2, c0 c0, c0 c1, c0 c2, c1 c1, c1 c2, c2 c2

// The statistics of one side: pixel count (in cells), colour mean and covariance (plus the
// noise floor on the diagonal).
struct SideStats {
  double n = 0;
  double mean[3] = {0, 0, 0};
  double cov[9] = {0};
};
SideStats sideStats(const double* sums, double noise_variance);
// The determinant of a side's covariance. The noise floor on the diagonal keeps it at least
// noise_variance^3, but rounding in the prefix sums can still push it to 0 or below: floored,
// so that its logarithm stays finite.
constexpr double kMinCovarianceDet = 1e-9;
double covarianceDet(const double* m);

constexpr int kMaxCell = 257;  // the largest cell whose column sums of 8-bit colours fit 16 bits

// A frame's colours on a grid of cells (box means over cell x cell pixels; the remainder at
// the right and bottom edges is left out), centred on the frame's mean colour.
class RegionGrid {
 public:
  void build(const cv::Mat& bgr, int cell);
  void buildHalf(const RegionGrid& finer);  // 2 x 2 cells of a finer grid each

  int cell() const { return cell_; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  const float* colour(int row, int col) const { return &means_[(static_cast<size_t>(row) * cols_ + col) * 3]; }
  const uint8_t* luma(int row) const { return &luma_[static_cast<size_t>(row) * cols_]; }  // BT.601, per cell
  const double* total() const { return total_; }
  // The moment sums of the sky side of `line` (full-resolution coordinates); the cell the line
  // crosses counts in part, in proportion to where it crosses, so the sums move smoothly.
  void skySideSums(const SplitLine& line, double* sums) const;

 private:
  void computeMoments();

  int cell_ = 1, rows_ = 0, cols_ = 0;
  std::vector<float> means_;    // rows x cols x 3, BGR box means
  std::vector<uint8_t> luma_;   // rows x cols
  std::vector<float> moments_;  // rows x cols x kPadded
  std::vector<float> down_;     // (rows + 1) x cols x kPadded: sums over the rows above
  std::vector<float> right_;    // rows x (cols + 1) x kPadded: sums over the columns left of
  std::vector<uint16_t> row_sums_;
  double total_[kMoments] = {0};
};

// A candidate horizon from the region search: its line and split score.
struct Hypothesis {
  double angle_deg, centre_distance, score;
};

struct SearchOptions {
  double max_angle_deg = 60;    // lines steeper than this are not searched
  int hypotheses = 3;           // distinct best lines kept
  double noise_variance = 4;    // colour noise floor (grey levels squared)
  double min_fraction = 0.01;   // each side holds at least this share of the frame
};

// The best distinct splits: a global search on `coarse` (angles every 4 deg, offsets every
// coarse cell), then each of the best `hypotheses` refined on `fine` (a quarter of those steps
// around it), best first.
std::vector<Hypothesis> searchSplits(const RegionGrid& fine, const RegionGrid& coarse, int width, int height,
                                     const SearchOptions& options);

}  // namespace horizon
}  // namespace rle_vision
