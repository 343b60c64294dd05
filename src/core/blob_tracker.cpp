#include "rle_vision/blob_tracker.h"

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
  scoreCandidates(regions, stamp_s);
  assign(regions.size());
  const size_t old_track_count = tracks_.size();
  emitBlobs(regions, stamp_s, blobs);
  ageTracks(old_track_count);
}

void BlobTracker::scoreCandidates(const std::vector<Region>& regions, double stamp_s) {
  // Score every same-class (track, region) pair inside the gates.
  candidates_.clear();
  const double log_max_ratio = std::log(std::max(options_.max_area_ratio, 1.0 + 1e-9));
  for (int t = 0; t < static_cast<int>(tracks_.size()); ++t) {
    const Track& track = tracks_[t];
    const double dt = std::max(0.0, stamp_s - track.last_seen_s);
    const double px = track.cx + track.vx * dt;
    const double py = track.cy + track.vy * dt;
    // A track unseen for a while may have drifted further: widen its gate.
    const double gate = options_.gate_px * (1.0 + 0.5 * track.missed);
    for (int r = 0; r < static_cast<int>(regions.size()); ++r) {
      const Region& region = regions[r];
      if (region.label != track.label) continue;
      const double distance = std::hypot(region.cx - px, region.cy - py);
      if (distance > gate) continue;
      const double log_ratio = std::fabs(std::log(static_cast<double>(region.area) / track.area));
      if (log_ratio > log_max_ratio) continue;
      candidates_.push_back({distance / gate + 0.5 * log_ratio / log_max_ratio, t, r});
    }
  }
}

void BlobTracker::assign(size_t region_count) {
  // Greedy global assignment, cheapest pair first (optimal for well separated objects).
  std::sort(candidates_.begin(), candidates_.end(),
            [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
  region_track_.assign(region_count, -1);
  track_matched_.assign(tracks_.size(), 0);
  for (const Candidate& c : candidates_) {
    if (region_track_[c.region] >= 0 || track_matched_[c.track]) continue;
    region_track_[c.region] = c.track;
    track_matched_[c.track] = 1;
  }
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
