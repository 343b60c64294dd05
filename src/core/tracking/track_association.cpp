#include "rle_vision/tracking/track_association.h"

#include <algorithm>
#include <limits>

namespace rle_vision {
namespace {

constexpr int64_t kCellRange = int64_t{1} << 20;  // cell coordinates kept in [-2^20, 2^20)

int64_t cellOf(double coordinate, double cell_px) {
  const double c = std::floor(coordinate / cell_px);
  return static_cast<int64_t>(std::min(std::max(c, -static_cast<double>(kCellRange)), static_cast<double>(kCellRange - 1)));
}

// Label, then row, then column: one class's cells of one row are contiguous in sorted order.
uint64_t cellKey(int label, int64_t row, int64_t column) {
  return (static_cast<uint64_t>(label & 0x3FFFFF) << 42) | (static_cast<uint64_t>(row + kCellRange) << 21) |
         static_cast<uint64_t>(column + kCellRange);
}

}  // namespace

void TrackAssociator::associate(const std::vector<TrackGate>& tracks, const std::vector<Region>& regions,
                                double max_area_ratio, double cell_px, std::vector<int>* region_track) {
  findPairings(tracks, regions, max_area_ratio, cell_px);
  assignCheapestFirst(regions.size(), region_track);
}

void TrackAssociator::findPairings(const std::vector<TrackGate>& tracks, const std::vector<Region>& regions,
                                   double max_area_ratio, double cell_px) {
  pairings_.clear();
  group_begin_.assign(tracks.size(), 0);
  group_end_.assign(tracks.size(), 0);
  if (tracks.empty() || regions.empty()) return;
  if (!(cell_px >= 1.0)) cell_px = 1.0;  // also catches NaN
  const double log_max_ratio = std::log(std::max(max_area_ratio, 1.0 + 1e-9));
  cells_.clear();
  int64_t min_row = kCellRange, max_row = -kCellRange, min_column = kCellRange, max_column = -kCellRange;
  for (int32_t r = 0; r < static_cast<int32_t>(regions.size()); ++r) {
    const int64_t row = cellOf(regions[r].cy, cell_px), column = cellOf(regions[r].cx, cell_px);
    min_row = std::min(min_row, row), max_row = std::max(max_row, row);
    min_column = std::min(min_column, column), max_column = std::max(max_column, column);
    cells_.emplace_back(cellKey(regions[r].label, row, column), r);
  }
  std::sort(cells_.begin(), cells_.end());
  // A small margin so that rounding never leaves out a cell holding a region on the gate.
  const double margin = 1e-9;
  for (int32_t t = 0; t < static_cast<int32_t>(tracks.size()); ++t) {
    const TrackGate& track = tracks[t];
    group_begin_[t] = group_end_[t] = pairings_.size();
    if (!std::isfinite(track.x) || !std::isfinite(track.y) || !(track.gate_px > 0)) continue;
    const int64_t row_lo = std::max(min_row, cellOf(track.y - track.gate_px - margin, cell_px));
    const int64_t row_hi = std::min(max_row, cellOf(track.y + track.gate_px + margin, cell_px));
    const int64_t column_lo = std::max(min_column, cellOf(track.x - track.gate_px - margin, cell_px));
    const int64_t column_hi = std::min(max_column, cellOf(track.x + track.gate_px + margin, cell_px));
    if (column_lo > column_hi) continue;
    for (int64_t row = row_lo; row <= row_hi; ++row) {
      const uint64_t last = cellKey(track.label, row, column_hi);
      auto it = std::lower_bound(cells_.begin(), cells_.end(),
                                 std::make_pair(cellKey(track.label, row, column_lo), std::numeric_limits<int32_t>::min()));
      for (; it != cells_.end() && it->first <= last; ++it) {
        double cost;
        if (scorePairing(track, regions[it->second], log_max_ratio, &cost)) {
          pairings_.push_back({cost, t, it->second});
        }
      }
    }
    group_end_[t] = pairings_.size();
  }
}

void TrackAssociator::assignCheapestFirst(size_t region_count, std::vector<int>* region_track) {
  // The same pairs, in the same order, as sorting every pair and taking each whose track and
  // region are both free, without sorting them all: each track's pairs form a heap, and a
  // heap of the tracks' cheapest pairs gives the next one. A track whose cheapest region is
  // taken offers its next; most tracks take their first, so the cost stays near the pairs'.
  region_track->assign(region_count, -1);
  const auto costlier = [](const TrackPairing& a, const TrackPairing& b) { return cheaperPairing(b, a); };
  heads_.clear();
  for (size_t t = 0; t < group_begin_.size(); ++t) {
    if (group_begin_[t] == group_end_[t]) continue;
    std::make_heap(pairings_.begin() + group_begin_[t], pairings_.begin() + group_end_[t], costlier);
    heads_.push_back(pairings_[group_begin_[t]]);
  }
  std::make_heap(heads_.begin(), heads_.end(), costlier);
  while (!heads_.empty()) {
    std::pop_heap(heads_.begin(), heads_.end(), costlier);
    const TrackPairing cheapest = heads_.back();
    heads_.pop_back();
    if ((*region_track)[cheapest.region] < 0) {
      (*region_track)[cheapest.region] = cheapest.track;  // the track is paired: its other pairs go
      continue;
    }
    const auto begin = pairings_.begin() + group_begin_[cheapest.track];
    auto end = pairings_.begin() + group_end_[cheapest.track];
    std::pop_heap(begin, end, costlier);  // drop the taken region's pair, the group's top
    --group_end_[cheapest.track];
    if (begin != --end) {
      heads_.push_back(*begin);
      std::push_heap(heads_.begin(), heads_.end(), costlier);
    }
  }
}

}  // namespace rle_vision
