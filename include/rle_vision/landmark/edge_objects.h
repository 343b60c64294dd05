// Run-length encoding of an edge image with the paper's two edge classes, and the connected
// edge objects made of touching runs (of either class).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/segment/regions.h"
#include "rle_vision/segment/run_length.h"

namespace rle_vision {

enum EdgeClass : uint8_t { kNoEdge = 0, kGrayEdge = 1, kSharpEdge = 2 };

// Edge objects are the connected edges; with `thin`, an object holds the crests of its edges.
// The parameters (gray_threshold, sharp_threshold, min_object_px, thin, adaptive, ...) are the
// OBJECTS group of landmark_params.def, with their defaults and meanings.
struct EdgeObjectOptions {
#define RLE_OBJECTS_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
  Connectivity connectivity = Connectivity::Eight;
};

struct EdgeObject {
  int32_t first_run = 0;  // its runs are runs()[first_run, first_run + run_count)
  int32_t run_count = 0;
  uint32_t pixels = 0;
  int left = 0, top = 0, right = 0, bottom = 0;
  double cx = 0, cy = 0;  // centroid, px
};

// Thins an edge image to its crests: a pixel >= min_value is kept when it is a local maximum
// (>= both neighbours) across the ridge, the direction (of four) where the magnitude curves
// most; all other pixels become 0. A step edge keeps a crest 1-2 px wide.
void thinEdges(const cv::Mat& edges, uint8_t min_value, cv::Mat* thin);

// Holds its buffers; reuse one instance per thread.
class EdgeObjectFinder {
 public:
  // `edges` is CV_8UC1 (e.g. Sobel5 output). Throws std::invalid_argument on other types.
  void find(const cv::Mat& edges, const EdgeObjectOptions& options);

  const std::vector<EdgeObject>& objects() const { return objects_; }
  // Runs grouped by object (row-major within an object); labels are EdgeClass values.
  const std::vector<Run>& runs() const { return object_runs_; }
  // Pixels and runs the objects are made of (crests when thinning), before the size filter.
  uint64_t edgePixels() const { return edge_pixels_; }
  uint64_t runCount() const { return held_runs_; }
  // The gray band's lowest threshold in the last find() (every tile's with adaptive edges).
  uint8_t grayThreshold() const { return used_gray_; }

 private:
  void grayThresholds(const cv::Mat& edges, const EdgeObjectOptions& options);
  void rowClasses(const uint8_t* edges, int width, int y, uint8_t sharp);
  void encodeEdges(const cv::Mat& edges, uint8_t sharp, std::vector<Run>* runs);
  void crestRuns(const cv::Mat& edges, uint8_t gray, uint8_t sharp);
  void collectObjects(const std::vector<Run>& held, uint32_t min_object_px);
  void groupRuns(const std::vector<Run>& held);

  std::vector<uint8_t> labels_;
  cv::Mat thin_;
  std::vector<Run> runs_, crest_runs_, object_runs_;
  std::vector<int32_t> row_starts_, object_of_root_, object_index_, fill_;
  uint64_t held_runs_ = 0;
  std::vector<Region> regions_;
  std::vector<EdgeObject> objects_;
  RegionBuilder builder_;
  uint64_t edge_pixels_ = 0;
  uint8_t used_gray_ = 0;
  int tile_ = 1, tile_cols_ = 1;
  std::vector<uint8_t> tile_gray_;  // the gray band's threshold per tile, row-major
  std::vector<uint8_t> pixel_gray_;  // rowClasses(): the thresholds of one tile row, per pixel
  int pixel_gray_tile_row_ = -1;     // the tile row pixel_gray_ holds (-1: none yet this frame)
};

}  // namespace rle_vision
