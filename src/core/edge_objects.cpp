#include "rle_vision/edge_objects.h"

#include <stdexcept>

#include "simd_dispatch.h"

namespace rle_vision {
namespace {

RLE_VISION_HOT
void edgeClasses(const uint8_t* __restrict edges, int width, uint8_t gray, uint8_t sharp, uint8_t* __restrict labels) {
  for (int x = 0; x < width; ++x) {
    labels[x] = static_cast<uint8_t>((edges[x] >= gray) + (edges[x] >= sharp));
  }
}

}  // namespace

void thinEdges(const cv::Mat& edges, uint8_t min_value, cv::Mat* thin) {
  thin->create(edges.size(), CV_8UC1);
  thin->setTo(0);
  const int w = edges.cols, h = edges.rows;
  // (dx, dy) of the four directions across which a crest is a maximum.
  static const int kDirections[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  for (int y = 1; y + 1 < h; ++y) {
    const uint8_t* row = edges.ptr<uint8_t>(y);
    uint8_t* out = thin->ptr<uint8_t>(y);
    for (int x = 1; x + 1 < w; ++x) {
      const int v = row[x];
      if (v < min_value) continue;
      int best_curvature = -1, best = 0;
      for (int d = 0; d < 4; ++d) {
        const int a = edges.at<uint8_t>(y + kDirections[d][1], x + kDirections[d][0]);
        const int b = edges.at<uint8_t>(y - kDirections[d][1], x - kDirections[d][0]);
        const int curvature = 2 * v - a - b;
        if (curvature > best_curvature) {
          best_curvature = curvature;
          best = d;
        }
      }
      const int a = edges.at<uint8_t>(y + kDirections[best][1], x + kDirections[best][0]);
      const int b = edges.at<uint8_t>(y - kDirections[best][1], x - kDirections[best][0]);
      if (v >= a && v >= b) out[x] = static_cast<uint8_t>(v);
    }
  }
}

void EdgeObjectFinder::find(const cv::Mat& edges, const EdgeObjectOptions& options) {
  if (edges.empty() || edges.type() != CV_8UC1) {
    throw std::invalid_argument("edge objects need a non-empty CV_8UC1 edge image");
  }
  const uint8_t gray = std::max<uint8_t>(1, options.gray_threshold);  // 0 would make every pixel an edge
  const uint8_t sharp = std::max(gray, options.sharp_threshold);
  if (options.thin) thinEdges(edges, gray, &thin_);
  const cv::Mat& source = options.thin ? thin_ : edges;
  labels_.resize(edges.cols);
  runs_.clear();
  row_starts_.resize(static_cast<size_t>(edges.rows) + 1);
  for (int y = 0; y < edges.rows; ++y) {
    row_starts_[y] = static_cast<int32_t>(runs_.size());
    edgeClasses(source.ptr<uint8_t>(y), edges.cols, gray, sharp, labels_.data());
    appendRowRuns(labels_.data(), edges.cols, y, &runs_);
  }
  row_starts_[edges.rows] = static_cast<int32_t>(runs_.size());
  edge_pixels_ = 0;
  for (const Run& run : runs_) edge_pixels_ += run.length();

  builder_.build(&runs_, row_starts_, options.connectivity, {0, options.min_object_px, options.min_object_px},
                 &regions_, /*join_labels=*/true);

  // Group the runs of each kept object together (a counting sort by object).
  objects_.clear();
  object_of_root_.assign(runs_.size(), -1);
  for (const Region& r : regions_) {
    object_of_root_[r.root_run] = static_cast<int32_t>(objects_.size());
    EdgeObject o;
    o.pixels = r.area;
    o.left = r.left;
    o.top = r.top;
    o.right = r.right;
    o.bottom = r.bottom;
    o.cx = r.cx;
    o.cy = r.cy;
    objects_.push_back(o);
  }
  for (const Run& run : runs_) {
    const int32_t object = object_of_root_[run.parent];
    if (object >= 0) ++objects_[object].run_count;
  }
  int32_t offset = 0;
  fill_.resize(objects_.size());
  for (size_t i = 0; i < objects_.size(); ++i) {
    objects_[i].first_run = offset;
    fill_[i] = offset;
    offset += objects_[i].run_count;
  }
  object_runs_.resize(offset);
  for (const Run& run : runs_) {
    const int32_t object = object_of_root_[run.parent];
    if (object >= 0) object_runs_[fill_[object]++] = run;
  }
}

}  // namespace rle_vision
