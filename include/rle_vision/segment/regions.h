// Connected regions from runs: union-find over runs that touch on adjacent rows, with area,
// bounding box, centroid and second moments accumulated from the runs in closed form.
#pragma once

#include <cstdint>
#include <vector>

#include "rle_vision/segment/run_length.h"

namespace rle_vision {

enum class Connectivity { Four = 4, Eight = 8 };

struct Region {
  int label = 0;        // 1 + colour class index
  uint32_t area = 0;    // pixels
  double cx = 0, cy = 0;  // centroid, px
  int left = 0, top = 0, right = 0, bottom = 0;  // bounding box, inclusive, px
  double var_xx = 0, var_yy = 0, var_xy = 0;  // central second moments / area, px^2
  double angle = 0;     // major-axis orientation, rad, in (-pi/2, pi/2], from +x towards +y
  // Lowest row of the region in column round(cx) (`bottom` when that column holds none of its
  // pixels): where an object standing on the ground touches it, whatever the camera's roll.
  int bottom_at_cx = 0;
  int32_t root_run = -1;  // index of the region's root run (its first run in row-major order)
};

// Which touching runs join one region.
enum class Joining {
  kSameLabel,  // runs of equal label (colour regions)
  kAnyLabel,   // runs of any non-zero labels; a region carries its first run's label (edge objects)
};

// Groups runs into regions. Holds scratch buffers; reuse one instance per thread.
class RegionBuilder {
 public:
  // `runs` and `row_starts` as encodeLabelRows() makes them. Runs that touch (share an edge
  // with Four, an edge or a corner with Eight) on adjacent rows join one region as `joining`
  // says. On return each run's parent is its region's root run. Regions come in row-major
  // order of their first pixel. `min_area_by_label[label]` (if that index exists) drops
  // smaller regions.
  void build(std::vector<Run>* runs, const std::vector<int32_t>& row_starts, Connectivity connectivity,
             const std::vector<uint32_t>& min_area_by_label, std::vector<Region>* regions,
             Joining joining = Joining::kSameLabel);
  // The last build's regions per label (index = label), of any size, dropped ones included.
  const std::vector<uint32_t>& regionCounts() const { return region_counts_; }

 private:
  void accumulateMoments(std::vector<Run>* runs);
  void emitRegions(const std::vector<Run>& runs, const std::vector<uint32_t>& min_area_by_label,
                   std::vector<Region>* regions);
  static void findBottoms(const std::vector<Run>& runs, const std::vector<int32_t>& row_starts,
                          std::vector<Region>* regions);

  struct Moments {
    int64_t area, sum_x, sum_y, sum_xx, sum_yy, sum_xy;
    int32_t left, top, right, bottom;
  };
  std::vector<int32_t> moment_index_;
  std::vector<Moments> moments_;
  std::vector<int32_t> roots_;  // each region's root run, in the order of moments_
  std::vector<uint32_t> region_counts_;
};

// Root of a run's set, with path halving.
inline int32_t findRoot(std::vector<Run>& runs, int32_t i) {
  while (runs[i].parent != i) {
    runs[i].parent = runs[runs[i].parent].parent;
    i = runs[i].parent;
  }
  return i;
}

}  // namespace rle_vision
