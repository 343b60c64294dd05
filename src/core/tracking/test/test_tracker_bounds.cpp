// A bounded frame: which regions are tracked (tracking size, number per class), association
// through a grid equal to scoring every pair, and the tracker on a very noisy frame.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/tracking/color_tracker.h"
#include "rle_vision/segment/region_load.h"
#include "rle_vision/segment/region_selection.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/tracking/track_association.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

Region region(int label, uint32_t area, double cx = 0, double cy = 0) {
  Region r;
  r.label = label;
  r.area = area;
  r.cx = cx;
  r.cy = cy;
  return r;
}

std::vector<uint32_t> areas(const std::vector<Region>& regions) {
  std::vector<uint32_t> out;
  for (const Region& r : regions) out.push_back(r.area);
  return out;
}

TEST(RegionSelector, TracksRegionsOfTrackingSizeInTheirOrder) {
  RegionSelector selector;
  std::vector<Region> tracked;
  selector.select({region(1, 5), region(1, 20), region(2, 19), region(1, 300), region(2, 21)}, RegionLimits(), &tracked);
  EXPECT_EQ(areas(tracked), (std::vector<uint32_t>{20, 300, 21}));  // 20 px is enough
  ASSERT_EQ(selector.counts().size(), 3u);
  EXPECT_EQ(selector.counts()[1].trackable, 2u);
  EXPECT_EQ(selector.counts()[1].tracked, 2u);
  EXPECT_EQ(selector.counts()[2].trackable, 1u);
  EXPECT_EQ(selector.counts()[2].tracked, 1u);
}

TEST(RegionSelector, AClassOverTheLimitKeepsItsLargestRegionsOthersAreUntouched) {
  RegionLimits limits;
  limits.min_track_area_px = 10;
  limits.max_regions_per_class = 3;
  // Class 1: four regions of tracking size (two more too small); of the two of 40 px at the
  // cut the earlier is kept. Class 2: three, at the limit.
  const std::vector<Region> regions = {region(1, 40), region(2, 11), region(1, 5), region(1, 90), region(2, 12),
                                       region(1, 40), region(1, 3),  region(1, 60), region(2, 13)};
  RegionSelector selector;
  std::vector<Region> tracked;
  selector.select(regions, limits, &tracked);
  EXPECT_EQ(areas(tracked), (std::vector<uint32_t>{40, 11, 90, 12, 60, 13}));
  EXPECT_EQ(selector.counts()[1].trackable, 4u);
  EXPECT_EQ(selector.counts()[1].tracked, 3u);
  EXPECT_EQ(selector.counts()[2].tracked, 3u);
  limits.max_regions_per_class = 4;
  selector.select(regions, limits, &tracked);
  EXPECT_EQ(areas(tracked), (std::vector<uint32_t>{40, 11, 90, 12, 40, 60, 13}));
  limits.max_regions_per_class = 0;
  selector.select(regions, limits, &tracked);
  EXPECT_TRUE(tracked.empty());
}

TEST(RegionLoadMonitor, ReportsOverloadedClassesPerWindowAndEachFirstTimeOnce) {
  RegionLoadMonitor monitor;
  std::vector<uint32_t> regions = {0, 12, 900};
  const uint32_t tracked = 43;  // the frame's blobs
  EXPECT_EQ(monitor.addFrame(regions, tracked, 500), std::vector<int>{2});
  regions[2] = 1200;
  EXPECT_TRUE(monitor.addFrame(regions, tracked, 500).empty());  // logged once, not every frame
  RegionLoadReport report = monitor.takeReport();
  ASSERT_EQ(report.overloaded.size(), 1u);
  EXPECT_EQ(report.overloaded[0].label, 2);
  EXPECT_EQ(report.overloaded[0].frames_overloaded, 2u);
  EXPECT_EQ(report.overloaded[0].most_regions, 1200u);
  EXPECT_EQ(report.regions, 1212u);
  EXPECT_EQ(report.tracked, 43u);
  regions[2] = 30;
  monitor.addFrame(regions, tracked, 500);
  EXPECT_TRUE(monitor.takeReport().overloaded.empty());  // the next window is clean
  EXPECT_EQ(overloadMessage("red", 1200, RegionLimits()),
            "too many regions for class red (1200 > max_regions_per_class 500): range too wide or image too noisy");
  ColorClass red, blue;
  red.name = "red", blue.name = "blue";
  const ColorTable table({red, blue});
  EXPECT_EQ(firstOverloadLog({}, regions, table, RegionLimits()), "");
  EXPECT_EQ(firstOverloadLog({1, 2}, {0, 700, 1200}, table, RegionLimits()),
            "too many regions for class red (700 > max_regions_per_class 500): range too wide or image too noisy; "
            "too many regions for class blue (1200 > max_regions_per_class 500): range too wide or image too noisy. "
            "Only the largest regions of at least min_track_area_px 20 px are tracked, up to that limit; further such "
            "frames are counted in diagnostics");
  // A class that never yields a blob (the floor's guard) is not tracked: never reported.
  ColorClass guard;
  guard.name = "floor_guard";
  guard.min_area_px = std::numeric_limits<uint32_t>::max();
  EXPECT_FALSE(yieldsBlobs(guard));
  EXPECT_TRUE(yieldsBlobs(red));
  EXPECT_EQ(firstOverloadLog({1}, {0, 4000, 10}, ColorTable({guard, blue}), RegionLimits()), "");
}

// The reference: every (track, region) pair scored and sorted, the tracker's code from before
// the grid (BlobTracker::scoreCandidates), copied word for word but for the tie order.
std::vector<TrackPairing> allPairings(const std::vector<TrackGate>& tracks, const std::vector<Region>& regions,
                                      double max_area_ratio) {
  std::vector<TrackPairing> candidates;
  const double log_max_ratio = std::log(std::max(max_area_ratio, 1.0 + 1e-9));
  for (int t = 0; t < static_cast<int>(tracks.size()); ++t) {
    const TrackGate& track = tracks[t];
    const double px = track.x, py = track.y, gate = track.gate_px;
    for (int r = 0; r < static_cast<int>(regions.size()); ++r) {
      const Region& region = regions[r];
      if (region.label != track.label) continue;
      const double distance = std::hypot(region.cx - px, region.cy - py);
      if (distance > gate) continue;
      const double log_ratio = std::fabs(std::log(static_cast<double>(region.area) / track.area));
      if (log_ratio > log_max_ratio) continue;
      candidates.push_back({distance / gate + 0.5 * log_ratio / log_max_ratio, t, r});
    }
  }
  std::sort(candidates.begin(), candidates.end(), cheaperPairing);
  return candidates;
}

// The reference assignment: every pair in order, taken when its track and region are free.
std::vector<int> greedyReference(const std::vector<TrackPairing>& sorted, size_t track_count, size_t region_count) {
  std::vector<int> region_track(region_count, -1);
  std::vector<char> track_paired(track_count, 0);
  for (const TrackPairing& p : sorted) {
    if (region_track[p.region] >= 0 || track_paired[p.track]) continue;
    region_track[p.region] = p.track;
    track_paired[p.track] = 1;
  }
  return region_track;
}

void expectSamePairings(std::vector<TrackPairing> found, const std::vector<TrackPairing>& reference) {
  std::sort(found.begin(), found.end(), cheaperPairing);
  ASSERT_EQ(found.size(), reference.size());
  for (size_t i = 0; i < found.size(); ++i) {
    EXPECT_EQ(found[i].track, reference[i].track) << i;
    EXPECT_EQ(found[i].region, reference[i].region) << i;
    EXPECT_EQ(found[i].cost, reference[i].cost) << i;
  }
}

TEST(TrackAssociator, PairsExactlyAsScoringAndSortingEveryPairDoes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-30, 670), y(-30, 510), gate(0, 150);
  std::uniform_int_distribution<int> label(1, 3), area(1, 400);
  TrackAssociator associator;
  std::vector<int> region_track;
  for (int trial = 0; trial < 40; ++trial) {
    // Small cases, then crowded ones: 300 tracks among 3000 regions, many pairs per track.
    const int track_count = trial < 30 ? 1 + trial : 300, region_count = trial < 30 ? 2 * trial : 3000;
    std::vector<TrackGate> tracks;
    for (int t = 0; t < track_count; ++t)
      tracks.push_back({label(rng), x(rng), y(rng), 1 + gate(rng), static_cast<uint32_t>(area(rng))});
    std::vector<Region> regions;
    for (int r = 0; r < region_count; ++r) regions.push_back(region(label(rng), area(rng), x(rng), y(rng)));
    // A region exactly on a gate's edge, one exactly 4x a track's area (the ratio limit), one
    // track exactly on a region, two tracks alike.
    if (region_count > 1 && track_count > 1) {
      regions[0].cx = tracks[0].x + tracks[0].gate_px;
      regions[0].cy = tracks[0].y;
      regions[0].label = tracks[0].label;
      regions[1] = region(tracks[0].label, 4 * tracks[0].area, tracks[0].x + 1, tracks[0].y);
      tracks.back().x = regions.back().cx, tracks.back().y = regions.back().cy;
      tracks[1] = tracks[0];
    }
    const double cell_px = trial % 3 == 0 ? 48.0 : trial % 3 == 1 ? 7.5 : 300.0;
    associator.associate(tracks, regions, 4.0, cell_px, &region_track);
    SCOPED_TRACE(trial);
    const std::vector<TrackPairing> reference = allPairings(tracks, regions, 4.0);
    expectSamePairings(associator.pairings(), reference);
    EXPECT_EQ(region_track, greedyReference(reference, tracks.size(), regions.size()));
    if (trial >= 30) EXPECT_GT(reference.size(), 1000u);
  }
}

TEST(TrackAssociator, EqualCostsGoToTheLowerTrackThenTheLowerRegion) {
  // Two tracks equally far from two regions: the result must not depend on the search order.
  const std::vector<TrackGate> tracks = {{1, 10, 0, 48, 100}, {1, -10, 0, 48, 100}};
  const std::vector<Region> regions = {region(1, 100, 0, 10), region(1, 100, 0, -10)};
  TrackAssociator associator;
  std::vector<int> region_track;
  associator.associate(tracks, regions, 4.0, 48.0, &region_track);
  EXPECT_EQ(region_track, (std::vector<int>{0, 1}));
  EXPECT_EQ(associator.pairings().size(), 4u);
}

TEST(BlobTracker, AnAreaChangeOfExactlyTheRatioLimitStillMatches) {
  // |log(100 / 25)| is exactly log(4); log(100) - log(25) would be one rounding step above.
  TrackerOptions options;
  options.limits.min_track_area_px = 1;
  std::vector<TrackedBlob> blobs;
  for (const uint32_t area : {6u, 25u, 8u}) {
    BlobTracker tracker(options);
    tracker.update({region(1, area, 50, 50)}, 0.0, &blobs);
    const uint32_t id = blobs.at(0).id;
    tracker.update({region(1, 4 * area, 50, 50)}, 1.0 / 30, &blobs);
    EXPECT_EQ(blobs.at(0).id, id) << area << " px to " << 4 * area << " px";
  }
}

TEST(BlobTracker, AVeryNoisyFrameIsTrackedWithinItsLimits) {
  // The built-in scene with sensor noise sigma 60 and CMVision's colors.txt (every class's
  // min_area_px 1): thousands of regions, a few dozen of tracking size.
  SceneConfig scene = loadSceneConfig(test::sourcePath("config/scene_default.yaml"));
  scene.noise_sigma = 60;
  const SceneSimulator simulator(scene);
  const ColorTable table(loadColorClasses(test::sourcePath("config/colors.txt")));
  Segmenter segmenter;
  BlobTracker tracker;
  std::vector<Region> regions;
  std::vector<TrackedBlob> blobs;
  const SimFrame frame = simulator.render(0, 0.0);
  segmenter.segment(frame.image, PixelFormat::BGR8, table, &regions);
  ASSERT_GT(regions.size(), 4000u);
  tracker.update(regions, 0.0, &blobs);
  std::vector<Region> expected;
  for (const Region& r : regions)
    if (r.area >= 20) expected.push_back(r);
  ASSERT_EQ(blobs.size(), expected.size());
  for (size_t i = 0; i < blobs.size(); ++i) EXPECT_EQ(blobs[i].region.root_run, expected[i].root_run);
  // The segmenter counts every region, each class far over the limit.
  uint32_t counted = 0;
  ASSERT_EQ(segmenter.regionCounts().size(), static_cast<size_t>(table.size()) + 1);
  for (int label = 1; label <= table.size(); ++label) {
    EXPECT_GT(segmenter.regionCounts()[label], 500u) << label;
    counted += segmenter.regionCounts()[label];
  }
  EXPECT_EQ(counted, regions.size());
  // The Tracker's ColorTracker does not build the regions under the tracking size: the same
  // counts, the same blobs.
  ColorTracker color_tracker;
  std::vector<TrackedBlob> same;
  color_tracker.process(frame.image, PixelFormat::BGR8, table, 0.0, &same);
  EXPECT_EQ(color_tracker.regionCounts(), segmenter.regionCounts());
  EXPECT_EQ(color_tracker.regions().size(), expected.size());
  ASSERT_EQ(same.size(), blobs.size());
  for (size_t i = 0; i < same.size(); ++i) {
    EXPECT_EQ(same[i].region.root_run, blobs[i].region.root_run);
    EXPECT_EQ(same[i].region.area, blobs[i].region.area);
    EXPECT_EQ(same[i].id, blobs[i].id);
  }
  // The same frame again: every blob keeps its id.
  std::vector<uint32_t> ids;
  for (const TrackedBlob& b : blobs) ids.push_back(b.id);
  tracker.update(regions, 1.0 / 30, &blobs);
  for (size_t i = 0; i < blobs.size(); ++i) EXPECT_EQ(blobs[i].id, ids[i]);
}

}  // namespace
}  // namespace rle_vision
