// Candidate (track, region) pairs for frame-to-frame tracking, found through a grid of cells
// so that the cost grows with the regions and the pairs inside the gates, not with tracks x
// regions: a noisy frame with thousands of regions must not stall the real-time tracker.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "rle_vision/segment/regions.h"

namespace rle_vision {

// Where a track is expected this frame and how far it may be from there.
struct TrackGate {
  int label = 0;
  double x = 0, y = 0;  // predicted centroid, px
  double gate_px = 0;   // largest centroid distance from (x, y); > 0
  uint32_t area = 1;    // area when last seen, px
};

struct TrackPairing {
  double cost;
  int track, region;
};

// The pair's cost when `region` passes the track's gates (same label, centroid within
// gate_px, area ratio within exp(log_max_area_ratio)): distance / gate + 0.5 * |log area
// ratio| / log max ratio, lower is better. The arithmetic is the tracker's from before the grid,
// operation for operation, so that pairs on a gate's edge fall the same way.
inline bool scorePairing(const TrackGate& track, const Region& region, double log_max_area_ratio, double* cost) {
  if (region.label != track.label) return false;
  const double distance = std::hypot(region.cx - track.x, region.cy - track.y);
  if (distance > track.gate_px) return false;
  const double log_ratio = std::fabs(std::log(static_cast<double>(region.area) / track.area));
  if (log_ratio > log_max_area_ratio) return false;
  *cost = distance / track.gate_px + 0.5 * log_ratio / log_max_area_ratio;
  return true;
}

// Cheapest first; equal costs by track, then region, so the result never depends on the
// order pairs were found in.
inline bool cheaperPairing(const TrackPairing& a, const TrackPairing& b) {
  if (a.cost != b.cost) return a.cost < b.cost;
  return a.track != b.track ? a.track < b.track : a.region < b.region;
}

// Holds scratch buffers; one instance per thread.
class TrackAssociator {
 public:
  // Pairs tracks with regions: the greedy global assignment, cheapest pair first in
  // cheaperPairing() order, each track and each region at most once. On return
  // region_track[r] is the track paired with region r, or -1. `cell_px` is the grid's cell
  // size (the base gate is a good choice). Tracks with a non-finite prediction or a gate that
  // is not positive get no pair.
  void associate(const std::vector<TrackGate>& tracks, const std::vector<Region>& regions, double max_area_ratio,
                 double cell_px, std::vector<int>* region_track);
  // Every pair scorePairing() accepted in the last call, grouped by track (not sorted).
  const std::vector<TrackPairing>& pairings() const { return pairings_; }

 private:
  void findPairings(const std::vector<TrackGate>& tracks, const std::vector<Region>& regions, double max_area_ratio,
                    double cell_px);
  void assignCheapestFirst(size_t region_count, std::vector<int>* region_track);

  std::vector<std::pair<uint64_t, int32_t>> cells_;  // (cell key, region index), sorted
  std::vector<TrackPairing> pairings_;
  std::vector<size_t> group_begin_, group_end_;      // per track: its pairs in pairings_
  std::vector<TrackPairing> heads_;                  // each unpaired track's cheapest pair left
};

}  // namespace rle_vision
