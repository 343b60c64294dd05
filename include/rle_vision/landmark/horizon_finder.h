// The horizon of a frame. With the colour image (HorizonDetector), from region evidence first:
// the lines that split the frame into two regions of distinct colour statistics (sky and
// ground) are found on a coarse grid of cells, each refined onto the frame's horizon edge at
// full resolution, and weighed by how much the split looks like sky above ground (colours
// apart, sky brighter, ground rougher and textured); the first that is convincing enough is
// the horizon. If none is, the long merged Hough lines are weighed the same way (where objects
// outweigh the sky in the colour statistics); else none is reported. Without the colour image
// (findHorizon), from the lines alone: long,
// not-steep lines from every edge object merge when collinear (the paper's horizon pieces),
// are fitted robustly, and the longest merged line that spans enough of the image wins.
#pragma once

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/landmark/detected_line.h"
#include "rle_vision/landmark/horizon_model.h"

namespace rle_vision {

// The parameters are the HORIZON group of landmark_params.def, with their defaults and meanings.
// `model`, when valid, weighs the candidate lines in order (the region splits, then the merged
// Hough lines) by the probability it gives: the first reaching its stop_probability is the
// horizon (the rest not refined), else the most probable when that reaches min_confidence;
// without one, the candidates are weighed by the product of the region evidence in order and
// the first convincing one wins.
struct HorizonOptions {
#define RLE_HORIZON_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
  HorizonModel model;
};

struct HorizonEstimate {
  bool found = false;      // a horizon is reported (region evidence: confidence >= min_confidence;
                           // lines alone: coverage >= min_coverage)
  ImageLine line;
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // extent of its supported part
  double length = 0;       // its support: px of merged pieces, or edge points (one per scan line)
  double coverage = 0;     // length / the line's length inside the image, 0..1
  double rms = 0;          // rms distance of the fitted pixels or points, px
  double confidence = 0;   // 0..1; with region evidence the product of the four below
  // The region evidence (with a colour image; each 0..1, 0.5 = no information):
  double separation = 0;       // the two sides' colours are apart (1 - Bhattacharyya coefficient)
  double sky_brighter = 0.5;   // P(a cell above is brighter than one below)
  double ground_rougher = 0.5; // P(an edge contrast below exceeds one above), relative to brightness
  double ground_textured = 0;  // share of pixels below above the noise floor
  uint32_t votes = 0, support = 0;  // Hough votes and support of the pieces, or edge points
  int pieces = 0;          // Hough lines merged into it
  HorizonFeatures features{};  // with a colour image: the evidence as the model reads it
};

// From the lines alone: merged collinear pieces, robustly refitted; confidence = coverage,
// lowered when the fit is loose (rms above 1.5 px).
HorizonEstimate findHorizon(const std::vector<DetectedLine>& lines, int width, int height,
                            const HorizonOptions& options);

// Holds scratch buffers; reuse one instance per thread.
class HorizonDetector {
 public:
  HorizonDetector();
  ~HorizonDetector();
  HorizonDetector(HorizonDetector&&) noexcept;
  HorizonDetector& operator=(HorizonDetector&&) noexcept;

  // `bgr` (CV_8UC3) and its `edges` (CV_8UC1, the 5x5 Sobel scaled by `edge_gain`), with the
  // lines found in them.
  HorizonEstimate detect(const cv::Mat& bgr, const cv::Mat& edges, double edge_gain,
                         const std::vector<DetectedLine>& lines, const HorizonOptions& options);

  // Every candidate line weighed (the region splits, then the merged Hough lines; all of them,
  // whatever the model's stop_probability), with its features, confidence and found flag as
  // detect() would give them: what a model learns from.
  std::vector<HorizonEstimate> candidates(const cv::Mat& bgr, const cv::Mat& edges, double edge_gain,
                                          const std::vector<DetectedLine>& lines, const HorizonOptions& options);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rle_vision
