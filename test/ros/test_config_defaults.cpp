// The live-tunable parameters start where the core's defaults are: for the landmark path they
// are generated from one table (the test checks the generation); for the others a default
// changed in one place and not the other fails here.
#include <gtest/gtest.h>

#include <type_traits>

#include "../../src/nodelets/ground_conversions.h"
#include "../../src/nodelets/landmark_conversions.h"
#include "rle_vision/EdgeDetectorConfig.h"
#include "rle_vision/GroundProjectorConfig.h"
#include "rle_vision/TrackerConfig.h"
#include "rle_vision/blob_tracker.h"
#include "rle_vision/segmenter.h"

namespace rle_vision {
namespace {

// The Landmark and EdgeDetector configs are generated from landmark_params.def by the .cfg
// files' own reading of it: every parameter's default and limits must be the table's, as the
// C++ preprocessor reads it (a parser slip in cfg/param_table.py fails here).
TEST(ConfigDefaults, LandmarkConfigIsTheParameterTable) {
  const LandmarkConfig& defaults = LandmarkConfig::__getDefault__();
  const LandmarkConfig& min = LandmarkConfig::__getMin__();
  const LandmarkConfig& max = LandmarkConfig::__getMax__();
  int checked = 0;
#define RLE_CHECK(key, type, default_value, lo, hi)                                  \
  ++checked;                                                                        \
  EXPECT_EQ(static_cast<type>(defaults.key), static_cast<type>(default_value)) << #key; \
  if (!std::is_same<type, bool>::value) {                                           \
    EXPECT_EQ(static_cast<double>(min.key), static_cast<double>(lo)) << #key;         \
    EXPECT_EQ(static_cast<double>(max.key), static_cast<double>(hi)) << #key;         \
  }
#define RLE_OBJECTS_PARAM(key, member, type, default_value, lo, hi, description) RLE_CHECK(key, type, default_value, lo, hi)
#define RLE_HOUGH_PARAM RLE_OBJECTS_PARAM
#define RLE_HORIZON_PARAM RLE_OBJECTS_PARAM
#define RLE_LEARNING_PARAM RLE_OBJECTS_PARAM
#define RLE_LEARNING_LOOP_PARAM RLE_OBJECTS_PARAM
#include "rle_vision/landmark_params.def"
  EXPECT_EQ(static_cast<size_t>(checked), LandmarkConfig::__getParamDescriptions__().size());
  // And the conversions give the core's defaults.
  EXPECT_EQ(optionsFromConfig(defaults).hough.min_votes, HoughOptions().min_votes);
  EXPECT_EQ(learningFromConfig(defaults).blend, LearningOptions().blend);
  EXPECT_EQ(learningLoopFromConfig(defaults).publish_period_s, LearningLoopOptions().publish_period_s);
}

TEST(ConfigDefaults, GroundProjectorConfigMatchesCoreDefaults) {
  const AttitudeFilterOptions from_config = attitudeFilterFromConfig(GroundProjectorConfig::__getDefault__());
  const AttitudeFilterOptions core;
  EXPECT_EQ(from_config.smoothing, core.smoothing);
  EXPECT_EQ(from_config.min_confidence, core.min_confidence);
  EXPECT_EQ(from_config.max_jump_deg, core.max_jump_deg);
  EXPECT_EQ(from_config.max_rejected, core.max_rejected);
  EXPECT_EQ(from_config.max_hold_s, core.max_hold_s);
}

TEST(ConfigDefaults, EdgeDetectorAndTrackerConfigsMatchCoreDefaults) {
  EXPECT_EQ(EdgeDetectorConfig::__getDefault__().edge_gain, LandmarkOptions().edge_gain);
  EXPECT_EQ(EdgeDetectorConfig::__getMin__().edge_gain, 0.05);
  const TrackerConfig tracker = TrackerConfig::__getDefault__();
  const TrackerOptions tracking;
  const SegmenterOptions segmenting;
  EXPECT_EQ(tracker.connectivity, static_cast<int>(segmenting.connectivity));
  EXPECT_EQ(static_cast<uint32_t>(tracker.min_area_px), segmenting.min_area_px);
  EXPECT_EQ(tracker.tracking_gate_px, tracking.gate_px);
  EXPECT_EQ(tracker.max_area_ratio, tracking.max_area_ratio);
  EXPECT_EQ(tracker.max_missed_frames, tracking.max_missed_frames);
  EXPECT_EQ(tracker.velocity_smoothing, tracking.velocity_smoothing);
  EXPECT_EQ(static_cast<uint32_t>(tracker.min_track_area_px), tracking.limits.min_track_area_px);
  EXPECT_EQ(static_cast<uint32_t>(tracker.max_regions_per_class), tracking.limits.max_regions_per_class);
}

}  // namespace
}  // namespace rle_vision
