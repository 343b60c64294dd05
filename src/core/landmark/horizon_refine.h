// A horizon hypothesis refined on the edge image, and the evidence that it is a horizon
// (private to the core).
#pragma once

#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "landmark/horizon_regions.h"

namespace rle_vision {
namespace horizon {

// How much a split looks like sky above ground, each part in [0, 1].
struct Evidence {
  double separation = 0;       // 1 - the Bhattacharyya coefficient of the sides' colour Gaussians
  double sky_brighter = 0.5;   // P(a sky cell is brighter than a ground cell), ties half
  double ground_rougher = 0.5; // P(a ground pixel's edge contrast exceeds a sky pixel's), relative to brightness
  double ground_textured = 0;  // share of ground pixels with an edge value above the noise floor
  double ground_textured_relative = 0;  // the same, edge contrast relative to brightness (Weber)
  double confidence() const { return separation * sky_brighter * ground_rougher * ground_textured; }
  // Along the line, the colour step between the cells just above and just below it over the
  // colour change a cell further into either side (median over the cell columns, or rows for
  // steep lines): a sky/ground boundary is a step, a line through cloud or texture is not.
  double local_step = 0;
  double sky_share = 0.5;      // share of the frame on the sky side
};

struct RefineOptions {
  double band_cells = 3;        // the edge search reaches this many grid cells either side
  double sky_percentile = 95;   // a horizon point beats this share of the sky's own edge values ...
  double edge_floor = 4;        // ... and the edge value of a noise-level step ...
  double peak_ratio = 0.5;      // ... and this share of the typical edge maximum along the band
  double inlier_px = 2;         // points this close to the line fit it
  double angle_range_deg = 3;   // the fit's angle search around the hypothesis
  int min_points = 10;          // fewer edge points: the hypothesis line stays
  double noise_variance = 4;    // colour noise floor (grey levels squared)
};

struct RefinedHorizon {
  SplitLine line;
  int points = 0;     // edge points found along the band
  int inliers = 0;    // of them on the fitted line
  double rms = 0;     // the inliers' rms distance from it, px
  int scanlines = 0;  // columns (rows for steep lines) the band crosses
  double t_min = 0, t_max = 0;  // the inliers' extent along the line (x cos a + y sin a)
  double edge_at_line = 0;    // the median edge value at the inliers
  double sky_edge_level = 0;  // the sky's own high edge value (its sky_percentile percentile)
  Evidence evidence;
};

// Holds scratch buffers; reuse one instance per thread.
class HorizonRefiner {
 public:
  // The hypothesis moved onto the frame's horizon edge: along every column (row, for steep
  // lines) across the band, the first edge maximum met coming from the sky side that beats
  // the thresholds above (the labelled top of the land; the stronger haze-to-ground step lies
  // below it), sub-pixel; then a robust line through those points.
  // Before refine() and evidence() on a frame: its texture samples, every 4th row and column of
  // the edge image and there the edge value over the brightness of its cell (log scale).
  void sampleTexture(const cv::Mat& edges, const RegionGrid& fine);
  RefinedHorizon refine(const cv::Mat& edges, const RegionGrid& fine, const Hypothesis& hypothesis,
                        const RefineOptions& options);
  // The same once per sky percentile (options.sky_percentile unused), each line handed to
  // `take` as soon as it is refined: the sky's edge values and the band measured once; a
  // percentile whose threshold or whose line (within the fit's resolution) an earlier one
  // already gave adds nothing. `take` returning true ends it: the later percentiles are not
  // refined (their fits and evidence are most of a candidate's cost).
  using RefinedSink = std::function<bool(const RefinedHorizon&)>;
  void refineEach(const cv::Mat& edges, const RegionGrid& fine, const Hypothesis& hypothesis, const RefineOptions& options,
                  const std::vector<double>& sky_percentiles, const RefinedSink& take);
  // The evidence for a line as the horizon, from the grid's colours and the texture samples.
  Evidence evidence(const cv::Mat& edges, const RegionGrid& fine, const SplitLine& line, const RefineOptions& options);

 private:
  struct Scan {
    int lo, hi;  // the band's samples on this scanline
  };
  void checkSamples(const cv::Mat& edges) const;  // throws cv::Exception without sampleTexture(edges)
  // The sky's edge histogram (away from the band), the band's scanlines and typical maximum.
  void measureBand(const cv::Mat& edges, const SplitLine& line, double band);
  double threshold(double sky_percentile, const RefineOptions& o);  // after measureBand()
  // The edge points beating `threshold` and the line through them (no evidence yet).
  RefinedHorizon fitAt(const cv::Mat& edges, const SplitLine& start, double threshold, const RefineOptions& o);
  double medianEdgeAtInliers(const cv::Mat& edges, const SplitLine& line, double inlier_px);
  double localStep(const RegionGrid& fine, const SplitLine& line, double noise);
  void scanPoints(const cv::Mat& edges, const SplitLine& line, double threshold);
  bool robustFit(const SplitLine& start, const RefineOptions& o, SplitLine* fitted);

  std::vector<Scan> scans_;
  std::vector<int> maxima_;
  std::vector<double> px_, py_, offsets_, weights_;
  std::vector<int> histogram_;
  std::vector<double> steps_, spreads_;
  std::vector<SplitLine> refined_lines_;  // refineEach(): the lines of this hypothesis so far
  double sky_edge_level_ = 0;
  int sky_histogram_[256] = {0}, sky_samples_ = 0;
  int typical_peak_ = -1;  // the band's median scanline maximum, -1: no scanline
  cv::Mat sampled_edges_, sampled_relative_;  // CV_8UC1, sampleTexture()
};

}  // namespace horizon
}  // namespace rle_vision
