// The paper's randomized Hough transform on run-length encoded edges, one edge object at a
// time (DESIGN.md section 3):
//  * random pixel pairs drawn from inside the object's runs (a run weighted by its length,
//    then a position in it: uniform over the object's pixels);
//  * each pair votes for its line in the (theta, intercept) space, intercept switching from y
//    to x at +-45 deg;
//  * neighbouring accumulator cells are grouped into peaks by comparing the lines they stand
//    for (angle and offset), which makes the space wrap where the parameters jump (theta
//    +-90 deg, and the intercept sign flip at +45 deg: the paper's topological band);
//  * a peak with at least min_votes votes is a line, refined by total least squares on the
//    object's pixels near it, and cut into its supported segments (gaps end a segment).
// The number of pairs per object follows eq. 2-4: p_i = n_i / p, S = n / p_i^2 for the
// shortest line wanted (n_i its pixels, p the object's pixels, n the votes wanted), with a
// cap; found lines claim their pixels, and further rounds sample, sized the same way, the
// pixels left unexplained (so large objects are not starved by the cap).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/edge_objects.h"
#include "rle_vision/line_fit.h"
#include "rle_vision/line_geometry.h"

namespace rle_vision {

struct ObjectRuns;

// An accumulator cell's line (internal): a x + b y + c = 0 with (a, b) = (-sin, cos) theta.
struct HoughCellLine {
  double a, b, c, theta;
};

struct HoughOptions {
  int min_votes = 5;                  // votes a peak needs to be a line (the paper's 5)
  double min_line_length_px = 30;     // shortest line wanted: sizes the sampling, filters output
  double edge_width_px = 1.5;         // edge pixels per pixel of line length (thinned ridge)
  double sampling_margin = 3;         // eq. 4 gives the mean vote count; this makes it likely
  int max_samples_per_object = 2000;  // cap on pairs per object and round
  double min_pair_distance_px = 10;   // closer pairs give poorly defined angles
  double theta_bin_deg = 1;
  double intercept_bin_px = 2;
  double peak_angle_deg = 2;          // grouping window: lines this close in angle ...
  double peak_distance_px = 3;        // ... and offset join one peak
  int max_lines_per_object = 32;
  int max_rounds = 4;                 // sampling rounds per object; each samples what is left
  int max_failed_peaks = 10;          // a round stops after this many peaks in a row lead nowhere
  double fit_distance_px = 4;         // pixels this close to a line refine it (covers a whole ridge)
  double max_gap_px = 8;              // a longer gap ends a line's segment
  double min_support_ratio = 0.5;     // support pixels per pixel of length, at least
  uint64_t seed = 1;
};

struct DetectedLine {
  ImageLine line;
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // supported segment
  double length = 0;                      // px
  uint32_t votes = 0;                     // Hough votes of its peak
  uint32_t support = 0;                   // object pixels within 1.5 px of the segment
  double rms = 0;                         // rms distance of the fitted pixels, px
  int object = -1;                        // edge object it comes from
  PointSums sums;                         // the fitted pixels (lets lines be merged and refitted)
};

struct HoughStats {
  uint64_t objects = 0;              // edge objects examined
  uint64_t sample_pairs = 0;         // pairs drawn, all objects
  uint64_t global_sample_pairs = 0;  // pairs eq. 4 asks of one Hough over all edge pixels
  uint64_t candidates = 0;           // peaks with enough votes
  uint64_t refinements = 0;          // candidates refined (the others repeated a found line)
};

// Holds scratch buffers; reuse one instance per thread. Deterministic: the same objects and
// options (seed included) give the same lines.
class RleHough {
 public:
  // With `edge_image` (the image the objects were found in), each segment's final fit uses
  // sub-pixel ridge centres (see ridge_fit.h), profile maxima below `ridge_strength` ignored.
  void detect(const EdgeObjectFinder& edges, int width, int height, const HoughOptions& options,
              std::vector<DetectedLine>* lines, HoughStats* stats, const cv::Mat* edge_image = nullptr,
              double ridge_strength = 60);

  // Pairs eq. 4 asks for an object of `object_pixels` to find lines of the minimum length.
  static uint64_t samplesFor(double object_pixels, const HoughOptions& options);

 private:
  struct Cell {
    uint32_t key;
    uint32_t votes;
  };
  void detectInObject(const EdgeObjectFinder& edges, int index, int width, int height,
                      const HoughOptions& options, std::vector<DetectedLine>* lines, HoughStats* stats,
                      const cv::Mat* edge_image, double ridge_strength);
  // Draws `samples` pixel pairs from the runs and fills cells_ (sorted by key).
  void vote(const Run* runs, int run_count, uint64_t samples, uint64_t seed, int width, int height,
            const HoughOptions& options);
  // Groups cells_ into peaks, refines them and claims their pixels; returns the lines added.
  int extractLines(const ObjectRuns& runs, const EdgeObject& object, int index, const HoughOptions& options,
                   const cv::Mat* edge_image, double ridge_strength, std::vector<DetectedLine>* found,
                   HoughStats* stats);
  // Appends the supported segments of the line the seed leads to; false (and nothing) when
  // lines found before have taken the pixels near the seed.
  bool refine(const ObjectRuns& runs, const ImageLine& seed, const HoughOptions& options,
              const cv::Mat* edge_image, double ridge_strength, std::vector<DetectedLine>* out) const;

  struct PixelXY {
    int16_t x, y;
  };
  std::vector<PixelXY> pixels_;
  std::vector<int32_t> row_first_;
  std::vector<uint8_t> claimed_;
  std::vector<Run> sample_runs_;
  std::vector<int> bucket_start_, fill_;  // cells_ of theta bin b: [bucket_start_[b], bucket_start_[b + 1])
  std::vector<double> bin_theta_, bin_normal_x_, bin_normal_y_;  // per theta bin
  double bins_for_deg_ = 0;                                       // the bin size they are for
  std::vector<HoughCellLine> cell_lines_;                         // per cell of cells_
  std::vector<char> used_;                                        // per cell: grouped or retired
  std::vector<uint32_t> order_, members_;
  int theta_bins_ = 0, intercept_bins_ = 0;
  double alpha_ = 0;
  std::vector<Cell> table_;
  std::vector<uint32_t> occupied_;  // slots of table_ in use
  std::vector<uint32_t> keys_;      // the cell each pair of a round votes for
  std::vector<Cell> cells_;
  std::vector<DetectedLine> refined_;
};

}  // namespace rle_vision
