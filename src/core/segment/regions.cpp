#include "rle_vision/segment/regions.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {
namespace {

// Sum of k^2 for k = 0..n (n >= -1).
inline int64_t sumOfSquares(int64_t n) { return n * (n + 1) * (2 * n + 1) / 6; }

// Major-axis orientation in (-pi/2, pi/2]. A noisy frame has thousands of one-pixel regions
// (no covariance, no spread): those skip atan2, with its exact result, +0.
inline double majorAxisAngle(double var_xx, double var_yy, double var_xy) {
  const double spread = var_xx - var_yy;
  if (var_xy == 0 && !std::signbit(var_xy) && spread == 0 && !std::signbit(spread)) return 0.0;
  const double angle = 0.5 * std::atan2(2.0 * var_xy, spread);
  return angle <= -M_PI / 2 ? angle + M_PI : angle;  // atan2(-0, negative) = -pi
}

}  // namespace

namespace {

// Joins the runs that touch on adjacent rows. Instantiated per connectivity and joining, so
// that the inner loop, run once per touching pair (tens of thousands on a noisy frame),
// carries no test of them.
template <int32_t kReach, bool kAnyLabel>
void joinTouchingRuns(std::vector<Run>& runs, const std::vector<int32_t>& row_starts) {
  const int rows = static_cast<int>(row_starts.size()) - 1;
  for (int y = 1; y < rows; ++y) {
    int32_t above = row_starts[y - 1];
    const int32_t above_end = row_starts[y];
    for (int32_t i = row_starts[y]; i < row_starts[y + 1]; ++i) {
      const Run& run = runs[i];
      // Runs above that end left of this one cannot touch it nor any run further right.
      while (above < above_end && runs[above].x1 + kReach < run.x0) ++above;
      // Union by smaller index (a root is its set's first run), with this run's root kept at
      // hand: only the runs above need finding.
      int32_t root = i;
      for (int32_t j = above; j < above_end && runs[j].x0 <= run.x1 + kReach; ++j) {
        if (!kAnyLabel && runs[j].label != run.label) continue;
        const int32_t other = findRoot(runs, j);
        if (other < root) {
          runs[root].parent = other;
          root = other;
        } else if (other > root) {
          runs[other].parent = root;
        }
      }
    }
  }
}

}  // namespace

void RegionBuilder::build(std::vector<Run>* runs_ptr, const std::vector<int32_t>& row_starts,
                          Connectivity connectivity, const std::vector<uint32_t>& min_area_by_label,
                          std::vector<Region>* regions, Joining joining) {
  std::vector<Run>& runs = *runs_ptr;
  regions->clear();
  const bool eight = connectivity == Connectivity::Eight, any_label = joining == Joining::kAnyLabel;
  if (eight) {
    any_label ? joinTouchingRuns<1, true>(runs, row_starts) : joinTouchingRuns<1, false>(runs, row_starts);
  } else {
    any_label ? joinTouchingRuns<0, true>(runs, row_starts) : joinTouchingRuns<0, false>(runs, row_starts);
  }
  accumulateMoments(&runs);
  emitRegions(runs, min_area_by_label, regions);
  findBottoms(runs, row_starts, regions);
}

void RegionBuilder::accumulateMoments(std::vector<Run>* runs_ptr) {
  // One pass over runs accumulates each region's moments; a root precedes its members.
  std::vector<Run>& runs = *runs_ptr;
  moment_index_.resize(runs.size());
  moments_.clear();
  roots_.clear();
  for (int32_t i = 0; i < static_cast<int32_t>(runs.size()); ++i) {
    const Run& run = runs[i];
    // A parent never has a larger index, and every earlier run already points at its root:
    // the root is one step away.
    const int32_t parent = run.parent;
    const int32_t root = parent == i ? i : runs[parent].parent;
    runs[i].parent = root;  // flatten: callers can read a run's region from its parent
    if (root == i) {
      moment_index_[i] = static_cast<int32_t>(moments_.size());
      roots_.push_back(i);
      moments_.push_back(Moments{0, 0, 0, 0, 0, 0, run.x0, run.y, run.x1, run.y});
    }
    Moments& m = moments_[moment_index_[root]];
    const int64_t n = run.length();
    const int64_t sx = (static_cast<int64_t>(run.x0) + run.x1) * n / 2;
    const int64_t y = run.y;
    m.area += n;
    m.sum_x += sx;
    m.sum_y += n * y;
    m.sum_xx += sumOfSquares(run.x1) - sumOfSquares(run.x0 - 1);
    m.sum_yy += n * y * y;
    m.sum_xy += sx * y;
    if (run.x0 < m.left) m.left = run.x0;
    if (run.x1 > m.right) m.right = run.x1;
    m.bottom = run.y;  // runs come in row order
  }
}

void RegionBuilder::emitRegions(const std::vector<Run>& runs, const std::vector<uint32_t>& min_area_by_label,
                                std::vector<Region>* regions) {
  // One step per region (its root), not per run: a noisy frame has thousands of tiny regions.
  region_counts_.clear();
  for (size_t k = 0; k < moments_.size(); ++k) {
    const Moments& m = moments_[k];
    const int32_t root = roots_[k];
    const int label = runs[root].label;
    if (label >= static_cast<int>(region_counts_.size())) region_counts_.resize(static_cast<size_t>(label) + 1, 0);
    ++region_counts_[label];
    if (label < static_cast<int>(min_area_by_label.size()) &&
        static_cast<uint64_t>(m.area) < min_area_by_label[label]) {
      continue;
    }
    Region r;
    r.label = label;
    r.area = static_cast<uint32_t>(m.area);
    const double inv = 1.0 / static_cast<double>(m.area);
    r.cx = m.sum_x * inv;
    r.cy = m.sum_y * inv;
    r.left = m.left;
    r.top = m.top;
    r.right = m.right;
    r.bottom = m.bottom;
    r.var_xx = m.sum_xx * inv - r.cx * r.cx;
    r.var_yy = m.sum_yy * inv - r.cy * r.cy;
    r.var_xy = m.sum_xy * inv - r.cx * r.cy;
    r.angle = majorAxisAngle(r.var_xx, r.var_yy, r.var_xy);
    r.root_run = root;
    r.bottom_at_cx = -1;
    regions->push_back(r);
  }
}

void RegionBuilder::findBottoms(const std::vector<Run>& runs, const std::vector<int32_t>& row_starts,
                                std::vector<Region>* regions) {
  // Per kept region, rows from its bottom up: the first run of the region covering its
  // centroid's column is the lowest one there. A row's runs are disjoint and ordered by x, so
  // a binary search finds the one run that may cover the column; the dropped regions (noise)
  // cost nothing.
  for (Region& region : *regions) {
    const int column = static_cast<int>(std::lround(region.cx));
    region.bottom_at_cx = region.bottom;
    for (int y = region.bottom; y >= region.top; --y) {
      const auto first = runs.begin() + row_starts[y], last = runs.begin() + row_starts[y + 1];
      const auto after = std::upper_bound(first, last, column, [](int c, const Run& run) { return c < run.x0; });
      if (after == first) continue;
      const Run& run = *(after - 1);
      if (run.x1 >= column && run.parent == region.root_run) {
        region.bottom_at_cx = y;
        break;
      }
    }
  }
}

}  // namespace rle_vision
