// The landmark pipeline of the paper's second half: 5x5 Sobel edges, RLE edge objects, the
// per-object randomized Hough, and the horizon.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/ground/camera_model.h"
#include "rle_vision/landmark/edge_objects.h"
#include "rle_vision/landmark/horizon_finder.h"
#include "rle_vision/landmark/rle_hough.h"
#include "rle_vision/edges/sobel5.h"

namespace rle_vision {

// edge_gain (the EDGE group of landmark_params.def) and the steps' own options.
struct LandmarkOptions {
#define RLE_EDGE_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
  EdgeObjectOptions objects;
  HoughOptions hough;
  HorizonOptions horizon;
};

// Reason the options are unusable (NaN, out of range), or "" when they are fine.
std::string validateLandmarkOptions(const LandmarkOptions& options);

struct LandmarkResult {
  std::vector<DetectedLine> lines;
  HorizonEstimate horizon;
  HoughStats hough;
  size_t edge_objects = 0;
  uint64_t edge_pixels = 0, edge_runs = 0;
  double sobel_ms = 0, objects_ms = 0, hough_ms = 0, horizon_ms = 0;  // time per stage
};

// Holds all buffers; reuse one instance per thread.
class LandmarkDetector {
 public:
  // From a colour (CV_8UC3) or gray (CV_8UC1) image: runs the 5x5 Sobel first. The horizon
  // comes from region evidence and edges (HorizonDetector; a gray image's evidence is its
  // brightness alone).
  void detectInImage(const cv::Mat& image, const LandmarkOptions& options, LandmarkResult* result);
  // From a colour image (CV_8UC3, BGR) and its edge image (CV_8UC1, the EdgeDetector's output
  // for it, at options.edge_gain). Without a usable `bgr` (empty, or another size) the lines
  // are found but no horizon: it cannot be weighed, and a horizon from lines alone locks onto
  // field lines indoors.
  void detect(const cv::Mat& bgr, const cv::Mat& edges, const LandmarkOptions& options, LandmarkResult* result);
  // From an edge image alone, as the paper: the horizon from the lines (findHorizon).
  void detectInEdges(const cv::Mat& edges, const LandmarkOptions& options, LandmarkResult* result);

  const cv::Mat& edges() const { return edges_; }
  const EdgeObjectFinder& edgeObjects() const { return finder_; }

 private:
  void findLines(const cv::Mat& edges, const LandmarkOptions& options, LandmarkResult* result);

  Sobel5 sobel_;
  EdgeObjectFinder finder_;
  RleHough hough_;
  HorizonDetector horizon_;
  cv::Mat edges_, gray_as_bgr_;
};

// Camera roll and pitch from a horizon (REP 103). Without a camera model (nullptr or invalid)
// the roll is -theta (square pixels assumed) and the pitch NaN.
void horizonAttitude(const ImageLine& horizon, const PinholeCamera* camera, double* roll, double* pitch);

}  // namespace rle_vision
