#include "rle_vision/landmark/edge_objects.h"

#include <algorithm>
#include <stdexcept>

#include "common/simd_dispatch.h"

namespace rle_vision {
namespace {

// Per pixel: 0 below its gray threshold, 1 in the gray band, 2 sharp. One pass over the whole
// row (the tiles' thresholds spread over their pixels): per-tile stretches left most of the
// work to the scalar tails.
RLE_VISION_HOT
void edgeClasses(const uint8_t* __restrict edges, int width, const uint8_t* __restrict gray, uint8_t sharp,
                 uint8_t* __restrict labels) {
  for (int x = 0; x < width; ++x) {
    labels[x] = static_cast<uint8_t>((edges[x] >= gray[x]) + (edges[x] >= sharp));
  }
}

// One row of thinEdges: up, mid, down are rows y - 1, y, y + 1; x in [1, width - 1).
// Branch-free within a block of kThinBlock pixels so that it vectorises; a block with no pixel
// reaching min_value holds no crest and is only cleared (most of a frame: sky, walls, floor).
constexpr int kThinBlock = 32;

RLE_VISION_HOT
void thinRow(const uint8_t* __restrict up, const uint8_t* __restrict mid, const uint8_t* __restrict down, int width,
             uint8_t min_value, uint8_t* __restrict out) {
  for (int first = 1; first + 1 < width; first += kThinBlock) {
    const int end = std::min(first + kThinBlock, width - 1);
    uint8_t strongest = 0;
    for (int x = first; x < end; ++x) strongest = std::max(strongest, mid[x]);
    if (strongest < min_value) {
      std::fill(out + first, out + end, 0);
      continue;
    }
    for (int x = first; x < end; ++x) {
      const int16_t v = mid[x];
      // The four directions' neighbour pairs: (1, 0), (0, 1), (1, 1), (1, -1).
      const int16_t a0 = mid[x + 1], b0 = mid[x - 1];
      const int16_t a1 = down[x], b1 = up[x];
      const int16_t a2 = down[x + 1], b2 = up[x - 1];
      const int16_t a3 = up[x + 1], b3 = down[x - 1];
      const int16_t c0 = 2 * v - a0 - b0, c1 = 2 * v - a1 - b1, c2 = 2 * v - a2 - b2, c3 = 2 * v - a3 - b3;
      // The direction of largest curvature (the first one on ties), and whether v is a maximum
      // across it. Integer selects and & (not && or bool) keep the loop vectorisable.
      const int16_t m0 = (v >= a0) & (v >= b0), m1 = (v >= a1) & (v >= b1);
      const int16_t m2 = (v >= a2) & (v >= b2), m3 = (v >= a3) & (v >= b3);
      const int16_t first_two = c0 >= c1, last_two = c2 >= c3;
      const int16_t c01 = first_two ? c0 : c1, m01 = first_two ? m0 : m1;
      const int16_t c23 = last_two ? c2 : c3, m23 = last_two ? m2 : m3;
      const int16_t keep = (c01 >= c23 ? m01 : m23) & (v >= min_value);
      out[x] = static_cast<uint8_t>(keep ? v : 0);
    }
  }
}

}  // namespace

void thinEdges(const cv::Mat& edges, uint8_t min_value, cv::Mat* thin) {
  thin->create(edges.size(), CV_8UC1);
  const int w = edges.cols, h = edges.rows;
  // Border pixels have no neighbours on one side: never crests.
  for (int y = 0; y < h; ++y) {
    uint8_t* out = thin->ptr<uint8_t>(y);
    if (y == 0 || y + 1 == h) {
      std::fill(out, out + w, 0);
      continue;
    }
    out[0] = 0;
    out[w - 1] = 0;
    thinRow(edges.ptr<uint8_t>(y - 1), edges.ptr<uint8_t>(y), edges.ptr<uint8_t>(y + 1), w, min_value, out);
  }
}

void EdgeObjectFinder::find(const cv::Mat& edges, const EdgeObjectOptions& options) {
  if (edges.empty() || edges.type() != CV_8UC1) {
    throw std::invalid_argument("edge objects need a non-empty CV_8UC1 edge image");
  }
  grayThresholds(edges, options);
  const uint8_t gray = used_gray_;
  const uint8_t sharp = std::max(options.gray_threshold, options.sharp_threshold);

  // Objects are the connected edges as they are (a thin bar's two edges are one object); with
  // thinning, the runs they hold are their crests.
  encodeEdges(edges, sharp, &runs_);
  builder_.build(&runs_, row_starts_, options.connectivity, {}, &regions_, Joining::kAnyLabel);
  object_of_root_.assign(runs_.size(), -1);
  for (size_t i = 0; i < regions_.size(); ++i) object_of_root_[regions_[i].root_run] = static_cast<int32_t>(i);
  if (options.thin) crestRuns(edges, gray, sharp);
  // The runs objects hold: every edge run, or the crest runs (each inside one edge run).
  const std::vector<Run>& held = options.thin ? crest_runs_ : runs_;
  collectObjects(held, options.min_object_px);
  groupRuns(held);
}

void EdgeObjectFinder::grayThresholds(const cv::Mat& edges, const EdgeObjectOptions& o) {
  const uint8_t fixed = std::max<uint8_t>(1, o.gray_threshold);  // 0 would make every pixel an edge
  tile_ = std::max(1, (std::min(edges.rows, edges.cols) + o.tiles - 1) / std::max(1, o.tiles));
  tile_cols_ = (edges.cols + tile_ - 1) / tile_;
  const int tile_rows = (edges.rows + tile_ - 1) / tile_;
  tile_gray_.assign(static_cast<size_t>(tile_rows) * tile_cols_, fixed);
  pixel_gray_tile_row_ = -1;
  used_gray_ = fixed;
  if (!o.adaptive) return;
  // Per tile, the median edge value (every second pixel): the noise and texture an edge must
  // stand out from.
  used_gray_ = 255;
  for (int ty = 0; ty < tile_rows; ++ty) {
    for (int tx = 0; tx < tile_cols_; ++tx) {
      int histogram[256] = {0}, samples = 0;
      for (int y = ty * tile_; y < std::min(edges.rows, (ty + 1) * tile_); y += 2) {
        const uint8_t* row = edges.ptr<uint8_t>(y);
        for (int x = tx * tile_; x < std::min(edges.cols, (tx + 1) * tile_); x += 2) ++histogram[row[x]];
        samples += (std::min(edges.cols, (tx + 1) * tile_) - tx * tile_ + 1) / 2;
      }
      int median = 0;
      for (int seen = 0; median < 255; ++median) {
        seen += histogram[median];
        if (2 * seen >= samples) break;
      }
      const double gray = std::min<double>(fixed, std::max<double>(o.min_value, o.noise_ratio * median));
      tile_gray_[static_cast<size_t>(ty) * tile_cols_ + tx] = static_cast<uint8_t>(std::lround(gray));
      used_gray_ = std::min(used_gray_, tile_gray_[static_cast<size_t>(ty) * tile_cols_ + tx]);
    }
  }
}

void EdgeObjectFinder::rowClasses(const uint8_t* edges, int width, int y, uint8_t sharp) {
  const int tile_row = y / tile_;
  if (tile_row != pixel_gray_tile_row_) {
    const uint8_t* gray = &tile_gray_[static_cast<size_t>(tile_row) * tile_cols_];
    pixel_gray_.resize(width);
    for (int x = 0; x < width; ++x) pixel_gray_[x] = gray[x / tile_];
    pixel_gray_tile_row_ = tile_row;
  }
  edgeClasses(edges, width, pixel_gray_.data(), sharp, labels_.data());
}

void EdgeObjectFinder::encodeEdges(const cv::Mat& edges, uint8_t sharp, std::vector<Run>* runs) {
  labels_.resize(edges.cols);
  runs->clear();
  row_starts_.resize(static_cast<size_t>(edges.rows) + 1);
  for (int y = 0; y < edges.rows; ++y) {
    row_starts_[y] = static_cast<int32_t>(runs->size());
    rowClasses(edges.ptr<uint8_t>(y), edges.cols, y, sharp);
    appendRowRuns(labels_.data(), edges.cols, y, runs);
  }
  row_starts_[edges.rows] = static_cast<int32_t>(runs->size());
}

void EdgeObjectFinder::crestRuns(const cv::Mat& edges, uint8_t gray, uint8_t sharp) {
  thinEdges(edges, gray, &thin_);  // the lowest tile threshold: each tile's own applies below
  crest_runs_.clear();
  for (int y = 0; y < edges.rows; ++y) {
    const size_t first = crest_runs_.size();
    rowClasses(thin_.ptr<uint8_t>(y), edges.cols, y, sharp);
    appendRowRuns(labels_.data(), edges.cols, y, &crest_runs_);
    // Each crest run lies inside an edge run of its row: that run's region is its object.
    int32_t edge_run = row_starts_[y];
    for (size_t i = first; i < crest_runs_.size(); ++i) {
      while (runs_[edge_run].x1 < crest_runs_[i].x0) ++edge_run;
      crest_runs_[i].parent = runs_[edge_run].parent;
    }
  }
}

void EdgeObjectFinder::collectObjects(const std::vector<Run>& held, uint32_t min_object_px) {
  // Object statistics from the runs held, then the minimum size.
  struct Stats {
    uint64_t pixels = 0;
    double sx = 0, sy = 0;
    int left = INT32_MAX, top = INT32_MAX, right = -1, bottom = -1;
    int32_t runs = 0;
  };
  std::vector<Stats> stats(regions_.size());
  edge_pixels_ = 0;
  for (const Run& run : held) {
    Stats& st = stats[object_of_root_[run.parent]];
    const int n = run.length();
    st.pixels += n;
    st.sx += 0.5 * (run.x0 + run.x1) * n;
    st.sy += static_cast<double>(run.y) * n;
    st.left = std::min(st.left, static_cast<int>(run.x0));
    st.right = std::max(st.right, static_cast<int>(run.x1));
    st.top = std::min(st.top, static_cast<int>(run.y));
    st.bottom = std::max(st.bottom, static_cast<int>(run.y));
    ++st.runs;
    edge_pixels_ += n;
  }
  objects_.clear();
  object_index_.assign(regions_.size(), -1);
  for (size_t r = 0; r < regions_.size(); ++r) {
    const Stats& st = stats[r];
    if (st.pixels < min_object_px) continue;
    object_index_[r] = static_cast<int32_t>(objects_.size());
    EdgeObject o;
    o.pixels = static_cast<uint32_t>(st.pixels);
    o.left = st.left;
    o.top = st.top;
    o.right = st.right;
    o.bottom = st.bottom;
    o.cx = st.sx / st.pixels;
    o.cy = st.sy / st.pixels;
    o.run_count = st.runs;
    objects_.push_back(o);
  }
}

void EdgeObjectFinder::groupRuns(const std::vector<Run>& held) {
  // Group the runs of each kept object together, row-major within it (a counting sort).
  int32_t offset = 0;
  fill_.resize(objects_.size());
  for (size_t i = 0; i < objects_.size(); ++i) {
    objects_[i].first_run = offset;
    fill_[i] = offset;
    offset += objects_[i].run_count;
  }
  object_runs_.resize(offset);
  for (const Run& run : held) {
    const int32_t object = object_index_[object_of_root_[run.parent]];
    if (object >= 0) object_runs_[fill_[object]++] = run;
  }
  held_runs_ = held.size();
}

}  // namespace rle_vision
