// Frame-to-frame tracking of regions: gated nearest neighbour on predicted centroid and size,
// giving stable ids and image velocities. A frame's cost is bounded: only regions of tracking
// size, at most a set number per class, are tracked, and pairs are found through a grid.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "rle_vision/segment/region_selection.h"
#include "rle_vision/segment/regions.h"
#include "rle_vision/tracking/track_association.h"

namespace rle_vision {

// gate_px (the largest centroid jump from the predicted position), max_area_ratio,
// max_missed_frames (a track unseen for longer is forgotten), velocity_smoothing: the TRACKER
// group of tracker_params.def, with their defaults and meanings.
struct TrackerOptions {
#define RLE_TRACKER_PARAM(key, member, type, default_value, min, max, description) \
  type member = static_cast<type>(default_value);
#include "rle_vision/params/tracker_params.def"
  RegionLimits limits;  // which regions are tracked (tracking size, number per class)
};

struct TrackedBlob {
  Region region;
  uint32_t id = 0;
  double vx = 0, vy = 0;  // px/s, 0 on first sight
  uint32_t age = 0;       // frames since first seen
  // The verifier's score in [0, 1] (verify/candidate_screen.h); NaN for a class without one.
  float score = std::numeric_limits<float>::quiet_NaN();
};

class BlobTracker {
 public:
  explicit BlobTracker(const TrackerOptions& options = TrackerOptions()) : options_(options) {}
  void setOptions(const TrackerOptions& options) { options_ = options; }

  // `stamp_s` is the image time in seconds. Time running backwards (a looped bag) starts over
  // and returns true from lastUpdateRestarted(). Blobs come in the order of `regions`, one per
  // region that options().limits lets through.
  void update(const std::vector<Region>& regions, double stamp_s, std::vector<TrackedBlob>* blobs);
  void reset();
  bool lastUpdateRestarted() const { return restarted_; }
  size_t trackCount() const { return tracks_.size(); }
  const TrackerOptions& options() const { return options_; }
  // The last frame's regions per label (1 + class index): of tracking size, and tracked.
  const std::vector<ClassRegionCount>& regionCounts() const { return selector_.counts(); }

 private:
  void associate(const std::vector<Region>& regions, double stamp_s);
  void emitBlobs(const std::vector<Region>& regions, double stamp_s, std::vector<TrackedBlob>* blobs);
  void ageTracks(size_t old_track_count);
  struct Track {
    uint32_t id;
    int label;
    double cx, cy, vx, vy;
    uint32_t area;
    uint64_t first_frame;
    double last_seen_s;
    int missed;
    bool has_velocity;
  };

  TrackerOptions options_;
  RegionSelector selector_;
  TrackAssociator associator_;
  std::vector<Track> tracks_;
  std::vector<Region> tracked_regions_;
  std::vector<TrackGate> gates_;
  std::vector<int> region_track_;
  std::vector<char> track_matched_;
  uint32_t next_id_ = 1;
  uint64_t frame_ = 0;
  double last_stamp_s_ = 0;
  bool has_stamp_ = false;
  bool restarted_ = false;
};

}  // namespace rle_vision
