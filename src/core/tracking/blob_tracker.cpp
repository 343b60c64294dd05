#include "rle_vision/tracking/blob_tracker.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {

void BlobTracker::reset() {
  tracks_.clear();
  has_stamp_ = false;
}

void BlobTracker::update(const std::vector<Region>& regions, double stamp_s,
                         std::vector<TrackedBlob>* blobs) {
  restarted_ = has_stamp_ && stamp_s < last_stamp_s_;
  if (restarted_) reset();
  has_stamp_ = true;
  last_stamp_s_ = stamp_s;
  ++frame_;
  selector_.select(regions, options_.limits, &tracked_regions_);
  associate(tracked_regions_, stamp_s);
  const size_t old_track_count = tracks_.size();
  emitBlobs(tracked_regions_, stamp_s, blobs);
  ageTracks(old_track_count);
}

void BlobTracker::associate(const std::vector<Region>& regions, double stamp_s) {
  // Greedy global assignment of the same-class (track, region) pairs inside the gates,
  // cheapest pair first (optimal for well separated objects).
  gates_.clear();
  for (const Track& track : tracks_) {
    const double dt = std::max(0.0, stamp_s - track.last_seen_s);
    // A track unseen for a while may have drifted further: widen its gate.
    gates_.push_back({track.label, track.cx + track.vx * dt, track.cy + track.vy * dt,
                      options_.gate_px * (1.0 + 0.5 * track.missed), track.area});
  }
  associator_.associate(gates_, regions, options_.max_area_ratio, options_.gate_px, &region_track_);
  track_matched_.assign(tracks_.size(), 0);
  for (int t : region_track_)
    if (t >= 0) track_matched_[t] = 1;
}

void BlobTracker::emitBlobs(const std::vector<Region>& regions, double stamp_s, std::vector<TrackedBlob>* blobs) {
  blobs->clear();
  blobs->reserve(regions.size());
  for (int r = 0; r < static_cast<int>(regions.size()); ++r) {
    const Region& region = regions[r];
    TrackedBlob blob;
    blob.region = region;
    const int t = region_track_[r];
    if (t >= 0) {
      Track& track = tracks_[t];
      const double dt = stamp_s - track.last_seen_s;
      if (dt > 0) {
        const double vx = (region.cx - track.cx) / dt;
        const double vy = (region.cy - track.cy) / dt;
        const double a = track.has_velocity ? options_.velocity_smoothing : 1.0;
        track.vx = a * vx + (1.0 - a) * track.vx;
        track.vy = a * vy + (1.0 - a) * track.vy;
        track.has_velocity = true;
      }
      track.cx = region.cx;
      track.cy = region.cy;
      track.area = region.area;
      track.last_seen_s = stamp_s;
      track.missed = 0;
      blob.id = track.id;
      blob.vx = track.vx;
      blob.vy = track.vy;
      blob.age = static_cast<uint32_t>(frame_ - track.first_frame);
    } else {
      tracks_.push_back(Track{next_id_++, region.label, region.cx, region.cy, 0.0, 0.0,
                              region.area, frame_, stamp_s, 0, false});
      blob.id = tracks_.back().id;
    }
    blobs->push_back(blob);
  }
}

void BlobTracker::ageTracks(size_t old_track_count) {
  // Age the tracks not seen this frame; forget those lost for too long.
  size_t kept = 0;
  for (size_t t = 0; t < tracks_.size(); ++t) {
    Track& track = tracks_[t];
    if (t < old_track_count && !track_matched_[t]) ++track.missed;
    if (track.missed <= options_.max_missed_frames) tracks_[kept++] = track;
  }
  tracks_.resize(kept);
}

}  // namespace rle_vision
