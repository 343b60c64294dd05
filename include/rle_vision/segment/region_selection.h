// Which of a frame's regions are worth tracking: a bounded number per colour class, however
// noisy the image or wide the colour range. Only regions of at least the tracking size are
// tracked, and of a class with more of them than the limit only its largest, so one bad frame
// costs bounded time. (Segmenter::regionCounts() counts every region, for diagnostics.)
#pragma once

#include <cstdint>
#include <vector>

#include "rle_vision/segment/regions.h"

namespace rle_vision {

// Smaller regions than min_track_area_px are counted but not tracked (CMVision's output drops
// regions under 20 px). At most max_regions_per_class regions of one class are tracked: its
// largest. A class with more regions than this in one frame, of any size, is reported as
// overloaded (a range too wide or an image too noisy; see region_load.h). The REGION_LIMITS
// group of tracker_params.def, with their defaults and meanings.
struct RegionLimits {
#define RLE_REGION_LIMITS_PARAM(key, member, type, default_value, min, max, description) \
  type member = static_cast<type>(default_value);
#include "rle_vision/params/tracker_params.def"
};

// One class's regions in the last frame.
struct ClassRegionCount {
  uint32_t trackable = 0;  // of tracking size
  uint32_t tracked = 0;    // of those, within max_regions_per_class
};

// Holds scratch buffers; one instance per thread.
class RegionSelector {
 public:
  // Copies the regions to track into `tracked`, in their order in `regions`. Among regions of
  // equal area at the limit, earlier ones are kept.
  void select(const std::vector<Region>& regions, const RegionLimits& limits, std::vector<Region>* tracked);
  // Indexed by label (1 + class index), sized to the largest label given in the last frame + 1.
  const std::vector<ClassRegionCount>& counts() const { return counts_; }

 private:
  // For each overloaded label: the smallest area kept, and how many of that area to keep.
  struct Cut {
    uint32_t area = 0;
    uint32_t ties_left = 0;
  };
  std::vector<ClassRegionCount> counts_;
  std::vector<Cut> cuts_;
  std::vector<uint32_t> areas_;
};

}  // namespace rle_vision
