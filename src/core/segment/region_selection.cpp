#include "rle_vision/segment/region_selection.h"

#include <algorithm>
#include <cstdint>
#include <functional>

namespace rle_vision {

void RegionSelector::select(const std::vector<Region>& regions, const RegionLimits& limits,
                            std::vector<Region>* tracked) {
  tracked->clear();
  int max_label = 0;
  for (const Region& r : regions) max_label = std::max(max_label, r.label);
  counts_.assign(static_cast<size_t>(max_label) + 1, ClassRegionCount());
  cuts_.assign(counts_.size(), Cut());
  auto trackable = [&](const Region& r) { return r.label >= 0 && r.area >= limits.min_track_area_px; };
  for (const Region& r : regions) {
    if (trackable(r)) ++counts_[r.label].trackable;
  }
  // An overloaded class keeps its `limit` largest regions: find the area at the cut (linear
  // time) and how many regions of exactly that area still fit.
  const uint32_t limit = limits.max_regions_per_class;
  for (int label = 0; label <= max_label; ++label) {
    ClassRegionCount& count = counts_[label];
    count.tracked = std::min(count.trackable, limit);
    if (count.trackable <= limit) continue;
    Cut& cut = cuts_[label];
    if (limit == 0) {
      cut.area = UINT32_MAX;
      continue;
    }
    areas_.clear();
    for (const Region& r : regions)
      if (r.label == label && trackable(r)) areas_.push_back(r.area);
    std::nth_element(areas_.begin(), areas_.begin() + (limit - 1), areas_.end(), std::greater<uint32_t>());
    cut.area = areas_[limit - 1];
    const auto larger = std::count_if(areas_.begin(), areas_.end(), [&](uint32_t a) { return a > cut.area; });
    cut.ties_left = limit - static_cast<uint32_t>(larger);
  }
  for (const Region& r : regions) {
    if (!trackable(r)) continue;
    if (counts_[r.label].trackable > limit) {
      Cut& cut = cuts_[r.label];
      if (r.area < cut.area) continue;
      if (r.area == cut.area) {
        if (cut.ties_left == 0) continue;
        --cut.ties_left;
      }
    }
    tracked->push_back(r);
  }
}

}  // namespace rle_vision
