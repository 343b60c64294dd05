// Tells the user when frames carry more regions than a colour class should have: per class,
// the frames overloaded (more regions of any size than RegionLimits::max_regions_per_class)
// between two reports and the largest region count among them. Thread-safe: frames add from
// one thread, reports are taken from another.
#pragma once

#include <cstdint>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "rle_vision/color/color_table.h"
#include "rle_vision/segment/region_selection.h"

namespace rle_vision {

struct ClassLoad {
  int label = 0;                 // 1 + class index
  uint32_t frames_overloaded = 0;  // since the last report
  uint32_t most_regions = 0;       // largest region count of those frames
  uint64_t frames_overloaded_total = 0;  // since start
};

struct RegionLoadReport {
  std::vector<ClassLoad> overloaded;  // classes overloaded since the last report, by label
  uint32_t regions = 0, tracked = 0;  // all classes, last frame
};

class RegionLoadMonitor {
 public:
  // `regions`: every region per label (Segmenter::regionCounts()); `tracked`: the frame's
  // blobs. Returns the labels overloaded for the first time since start (to be logged once
  // each).
  std::vector<int> addFrame(const std::vector<uint32_t>& regions, uint32_t tracked, uint32_t max_regions_per_class);
  // What happened since the last call.
  RegionLoadReport takeReport();

 private:
  std::mutex mutex_;
  std::vector<ClassLoad> loads_;  // indexed by label
  RegionLoadReport last_frame_;
};

// A class whose regions never become blobs (a class that only takes pixels from the classes
// after it, such as the floor's guard: its min_area_px is the largest there is) is not tracked,
// so it is never reported as overloaded.
inline bool yieldsBlobs(const ColorClass& c) { return c.min_area_px != std::numeric_limits<uint32_t>::max(); }

// What to tell the user about a class with `regions` regions in one frame, over the limit.
std::string overloadMessage(const std::string& class_name, uint32_t regions, const RegionLimits& limits);

// The log line for classes overloaded for the first time (`labels`, from addFrame()), with
// their counts in `regions` and their names in `table`; "" when `labels` is empty.
std::string firstOverloadLog(const std::vector<int>& labels, const std::vector<uint32_t>& regions,
                             const ColorTable& table, const RegionLimits& limits);

}  // namespace rle_vision
