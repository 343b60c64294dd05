// Frame-to-frame tracking: stable ids on a moving simulated scene, velocities, restarts.
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/segment/segmenter.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

Region square(int label, double cx, double cy, uint32_t area = 100) {
  Region r;
  r.label = label;
  r.cx = cx;
  r.cy = cy;
  r.area = area;
  return r;
}

TEST(BlobTracker, IdsStayStableAsSimulatedObstaclesMove) {
  SceneConfig scene = loadSceneConfig(test::sourcePath("config/scene_default.yaml"));
  scene.noise_sigma = 2.0;
  for (SceneBox& box : scene.boxes) {  // every box moves, sideways, at different speeds
    box.sway_y_m = 0.1 + 0.02 * (&box - &scene.boxes[0]);
    box.sway_period_s = 3.0;
  }
  const SceneSimulator simulator(scene);
  const ColorTable table(loadColorClasses(test::sourcePath("config/colors.yaml")));
  Segmenter segmenter;
  BlobTracker tracker;
  std::vector<Region> regions;
  std::vector<TrackedBlob> blobs;
  std::map<std::string, uint32_t> id_of_box;
  int checked = 0;
  for (int frame = 0; frame < 90; ++frame) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    segmenter.segment(f.image, PixelFormat::BGR8, table, &regions);
    tracker.update(regions, frame / 30.0, &blobs);
    std::set<uint32_t> ids_this_frame;
    for (const BoxTruth& box : test::isolatedBoxes(f, table)) {
      if (box.area < 200) continue;
      const Region* r = test::regionOfBox(regions, table, box, 3.0);
      ASSERT_NE(r, nullptr) << box.name;
      const TrackedBlob& blob = blobs[r - regions.data()];
      ASSERT_TRUE(ids_this_frame.insert(blob.id).second) << "two boxes share id " << blob.id;
      auto known = id_of_box.find(box.name);
      if (known == id_of_box.end()) {
        id_of_box[box.name] = blob.id;
      } else {
        ASSERT_EQ(blob.id, known->second) << box.name << " changed id at frame " << frame;
        EXPECT_GT(blob.age, 0u);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(BlobTracker, EstimatesImageVelocity) {
  BlobTracker tracker;
  std::vector<TrackedBlob> blobs;
  for (int frame = 0; frame < 10; ++frame) {
    tracker.update({square(1, 100 + 2.0 * frame, 50 - 1.0 * frame)}, frame / 30.0, &blobs);
    ASSERT_EQ(blobs.size(), 1u);
    EXPECT_EQ(blobs[0].id, 1u);
    EXPECT_EQ(blobs[0].age, static_cast<uint32_t>(frame));
    if (frame == 0) {
      EXPECT_EQ(blobs[0].vx, 0.0);  // 0 on first sight
    } else {
      EXPECT_NEAR(blobs[0].vx, 60.0, 1e-6);
      EXPECT_NEAR(blobs[0].vy, -30.0, 1e-6);
    }
  }
}

TEST(BlobTracker, CrossingObjectsOfDifferentClassesKeepTheirIds) {
  BlobTracker tracker;
  std::vector<TrackedBlob> blobs;
  for (int frame = 0; frame < 20; ++frame) {
    const double t = frame / 30.0;
    tracker.update({square(1, 100 + 5.0 * frame, 50), square(2, 200 - 5.0 * frame, 50)}, t, &blobs);
    ASSERT_EQ(blobs.size(), 2u);
    EXPECT_EQ(blobs[0].id, 1u);
    EXPECT_EQ(blobs[1].id, 2u);
  }
}

TEST(BlobTracker, GateAndSizeRejectJumps) {
  TrackerOptions options;
  options.gate_px = 20;
  options.max_area_ratio = 2;
  BlobTracker tracker(options);
  std::vector<TrackedBlob> blobs;
  tracker.update({square(1, 10, 10)}, 0.0, &blobs);
  tracker.update({square(1, 50, 10)}, 0.1, &blobs);  // 40 px jump: a new object
  EXPECT_EQ(blobs[0].id, 2u);
  tracker.update({square(1, 52, 10, 1000)}, 0.2, &blobs);  // 10x the area: a new object
  EXPECT_EQ(blobs[0].id, 3u);
}

TEST(BlobTracker, ReacquiresWithinMissedFramesAndForgetsAfter) {
  TrackerOptions options;
  options.max_missed_frames = 3;
  BlobTracker tracker(options);
  std::vector<TrackedBlob> blobs;
  tracker.update({square(1, 10, 10)}, 0.0, &blobs);
  tracker.update({}, 0.1, &blobs);
  tracker.update({}, 0.2, &blobs);
  tracker.update({square(1, 11, 10)}, 0.3, &blobs);
  EXPECT_EQ(blobs[0].id, 1u);
  for (int i = 0; i < 4; ++i) tracker.update({}, 0.4 + 0.1 * i, &blobs);
  EXPECT_EQ(tracker.trackCount(), 0u);
  tracker.update({square(1, 11, 10)}, 1.0, &blobs);
  EXPECT_EQ(blobs[0].id, 2u);
}

TEST(BlobTracker, TimeGoingBackwardsRestarts) {
  BlobTracker tracker;
  std::vector<TrackedBlob> blobs;
  tracker.update({square(1, 10, 10)}, 5.0, &blobs);
  tracker.update({square(1, 11, 10)}, 5.1, &blobs);
  EXPECT_FALSE(tracker.lastUpdateRestarted());
  tracker.update({square(1, 11, 10)}, 1.0, &blobs);  // a looped bag
  EXPECT_TRUE(tracker.lastUpdateRestarted());
  EXPECT_EQ(blobs[0].age, 0u);
  EXPECT_EQ(blobs[0].vx, 0.0);
}

}  // namespace
}  // namespace rle_vision
