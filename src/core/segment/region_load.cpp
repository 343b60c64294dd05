#include "rle_vision/segment/region_load.h"

#include <algorithm>

namespace rle_vision {

std::vector<int> RegionLoadMonitor::addFrame(const std::vector<uint32_t>& regions, uint32_t tracked,
                                             uint32_t max_regions_per_class) {
  std::vector<int> first_time;
  std::lock_guard<std::mutex> lock(mutex_);
  if (loads_.size() < regions.size()) loads_.resize(regions.size());
  last_frame_.regions = 0;
  last_frame_.tracked = tracked;
  for (size_t label = 0; label < regions.size(); ++label) {
    last_frame_.regions += regions[label];
    if (regions[label] <= max_regions_per_class) continue;
    ClassLoad& load = loads_[label];
    load.label = static_cast<int>(label);
    if (load.frames_overloaded_total == 0) first_time.push_back(load.label);
    ++load.frames_overloaded;
    ++load.frames_overloaded_total;
    load.most_regions = std::max(load.most_regions, regions[label]);
  }
  return first_time;
}

RegionLoadReport RegionLoadMonitor::takeReport() {
  std::lock_guard<std::mutex> lock(mutex_);
  RegionLoadReport report = last_frame_;
  for (ClassLoad& load : loads_) {
    if (load.frames_overloaded == 0) continue;
    report.overloaded.push_back(load);
    load.frames_overloaded = 0;
    load.most_regions = 0;
  }
  return report;
}

std::string overloadMessage(const std::string& class_name, uint32_t regions, const RegionLimits& limits) {
  return "too many regions for class " + class_name + " (" + std::to_string(regions) + " > max_regions_per_class " +
         std::to_string(limits.max_regions_per_class) + "): range too wide or image too noisy";
}

std::string firstOverloadLog(const std::vector<int>& labels, const std::vector<uint32_t>& regions,
                             const ColorTable& table, const RegionLimits& limits) {
  std::string text;
  for (int label : labels) {
    if (label < 1 || label > table.size() || static_cast<size_t>(label) >= regions.size()) continue;
    if (!yieldsBlobs(table.classes()[label - 1])) continue;
    text += (text.empty() ? "" : "; ") + overloadMessage(table.classes()[label - 1].name, regions[label], limits);
  }
  if (text.empty()) return text;
  return text + ". Only the largest regions of at least min_track_area_px " + std::to_string(limits.min_track_area_px) +
         " px are tracked, up to that limit; further such frames are counted in diagnostics";
}

}  // namespace rle_vision
