// The paper's randomized Hough transform on run-length encoded edges, one edge object at a
// time (docs/ARCHITECTURE.md, Conventions):
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
// pixels left unexplained (so large objects are not starved by the cap). Work per frame is
// bounded: at most max_refinements_per_frame candidates are fitted, objects taken largest first
// (the longest lines first); the objects the budget does not reach are counted in the stats.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/landmark/detected_line.h"
#include "rle_vision/landmark/edge_objects.h"
#include "rle_vision/landmark/hough_options.h"

namespace rle_vision {

struct HoughStats {
  uint64_t objects = 0;              // edge objects examined
  uint64_t sample_pairs = 0;         // pairs drawn, all objects
  uint64_t global_sample_pairs = 0;  // pairs eq. 4 asks of one Hough over all edge pixels
  uint64_t candidates = 0;           // peaks with enough votes
  uint64_t refinements = 0;          // candidates refined (the others repeated a found line)
  // The frame's work budget (max_refinements_per_frame) ran out: candidates were left unfitted,
  // in objects_skipped objects not examined at all and perhaps in the one it ran out in.
  bool budget_exhausted = false;
  uint64_t objects_skipped = 0;
};

// Holds scratch buffers; reuse one instance per thread. Deterministic: the same objects and
// options (seed included) give the same lines.
class RleHough {
 public:
  RleHough();
  ~RleHough();
  RleHough(RleHough&&) noexcept;
  RleHough& operator=(RleHough&&) noexcept;

  // Lines of the objects `edges` found in `edge_image` (CV_8UC1): each segment's final fit
  // uses sub-pixel ridge centres on the edge image (see ridge_fit.h), profile maxima below
  // `ridge_strength` ignored.
  void detect(const EdgeObjectFinder& edges, const cv::Mat& edge_image, double ridge_strength,
              const HoughOptions& options, std::vector<DetectedLine>* lines, HoughStats* stats);

  // The same without the edge image (a width x height image): each segment's final fit is a
  // least-squares fit of its run pixels (faster, less precise).
  void detectOnRuns(const EdgeObjectFinder& edges, int width, int height, const HoughOptions& options,
                    std::vector<DetectedLine>* lines, HoughStats* stats);

  // Pairs eq. 4 asks for an object of `object_pixels` to find lines of the minimum length.
  static uint64_t samplesFor(double object_pixels, const HoughOptions& options);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rle_vision
