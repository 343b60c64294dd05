// The live-tunable parameters start where the core's defaults are: every node's are generated
// from its one table (include/rle_vision/params/*.def); the tests check the generation (a
// parser slip in cfg/param_table.py fails here) and the conversions.
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include "../../src/nodelets/ground_conversions.h"
#include "../../src/nodelets/landmark_conversions.h"
#include "../../src/nodelets/tracker_conversions.h"
#include "rle_vision/EdgeDetectorConfig.h"
#include "rle_vision/GroundProjectorConfig.h"
#include "rle_vision/TrackerConfig.h"
#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/segment/segmenter.h"

namespace rle_vision {
namespace {

// A node's generated config against its table, as the C++ preprocessor reads the table (a
// parser slip in cfg/param_table.py fails here): every parameter's default and limits, and no
// parameter more or less. Open the check, define the table's macros as RLE_CHECK, include it.
#define RLE_CHECK_CONFIG(Config)                      \
  const Config& defaults = Config::__getDefault__(); \
  const Config& min = Config::__getMin__();          \
  const Config& max = Config::__getMax__();          \
  int checked = 0;
#define RLE_CHECK(key, type, default_value, lo, hi)                                      \
  ++checked;                                                                             \
  EXPECT_EQ(static_cast<type>(defaults.key), static_cast<type>(default_value)) << #key; \
  if (!std::is_same<type, bool>::value) {                                                \
    EXPECT_EQ(static_cast<double>(min.key), static_cast<double>(lo)) << #key;            \
    EXPECT_EQ(static_cast<double>(max.key), static_cast<double>(hi)) << #key;            \
  }
#define RLE_CHECKED_ALL(Config) EXPECT_EQ(static_cast<size_t>(checked), Config::__getParamDescriptions__().size())

TEST(ConfigDefaults, LandmarkConfigIsTheParameterTable) {
  RLE_CHECK_CONFIG(LandmarkConfig)
#define RLE_OBJECTS_PARAM(key, member, type, default_value, lo, hi, description) RLE_CHECK(key, type, default_value, lo, hi)
#define RLE_HOUGH_PARAM RLE_OBJECTS_PARAM
#define RLE_HORIZON_PARAM RLE_OBJECTS_PARAM
#define RLE_LEARNING_PARAM RLE_OBJECTS_PARAM
#define RLE_LEARNING_LOOP_PARAM RLE_OBJECTS_PARAM
#define RLE_FIELD_COLOR_PARAM RLE_OBJECTS_PARAM
#define RLE_FIELD_BOUNDARY_PARAM RLE_OBJECTS_PARAM
#include "rle_vision/params/landmark_params.def"
  RLE_CHECKED_ALL(LandmarkConfig);
  // And the conversions give the core's defaults.
  EXPECT_EQ(optionsFromConfig(defaults).hough.min_votes, HoughOptions().min_votes);
  EXPECT_EQ(learningFromConfig(defaults).blend, LearningOptions().blend);
  EXPECT_EQ(learningLoopFromConfig(defaults).publish_period_s, LearningLoopOptions().publish_period_s);
  EXPECT_EQ(fieldFromConfig(defaults).colour.blend, FieldColorOptions().blend);
  EXPECT_EQ(fieldFromConfig(defaults).boundary.inlier_px, FieldBoundaryOptions().inlier_px);
}

// The Tracker's and the GroundProjector's configs are generated from their tables in the same
// way: the same check, and the conversions give the core's defaults.
TEST(ConfigDefaults, TrackerConfigIsItsParameterTable) {
  RLE_CHECK_CONFIG(TrackerConfig)
#define RLE_SEGMENTER_PARAM(key, member, type, default_value, lo, hi, description) RLE_CHECK(key, type, default_value, lo, hi)
#define RLE_REGION_LIMITS_PARAM RLE_SEGMENTER_PARAM
#define RLE_TRACKER_PARAM RLE_SEGMENTER_PARAM
#include "rle_vision/params/tracker_params.def"
  RLE_CHECKED_ALL(TrackerConfig);
  SegmenterOptions segmenting;
  TrackerOptions tracking;
  segmenting.min_area_px = 99;
  tracking.gate_px = -1;
  optionsFromConfig(defaults, &segmenting, &tracking);
  EXPECT_EQ(segmenting.connectivity, SegmenterOptions().connectivity);
  EXPECT_EQ(segmenting.min_area_px, SegmenterOptions().min_area_px);
  EXPECT_EQ(tracking.gate_px, TrackerOptions().gate_px);
  EXPECT_EQ(tracking.limits.max_regions_per_class, RegionLimits().max_regions_per_class);
  // And back: the config that shows the options in effect holds them.
  TrackerConfig shown = defaults;
  TrackerOptions changed;
  changed.gate_px = 12.5;
  changed.limits.min_track_area_px = 7;
  configFromOptions(SegmenterOptions(), changed, &shown);
  EXPECT_EQ(shown.tracking_gate_px, 12.5);
  EXPECT_EQ(shown.min_track_area_px, 7);
  shown.velocity_smoothing = std::nan("");
  EXPECT_EQ(nonFiniteTrackerParam(shown), "velocity_smoothing");
  EXPECT_EQ(nonFiniteTrackerParam(defaults), "");
}

TEST(ConfigDefaults, GroundProjectorConfigIsItsParameterTable) {
  RLE_CHECK_CONFIG(GroundProjectorConfig)
#define RLE_GROUND_PARAM(key, member, type, default_value, lo, hi, description) RLE_CHECK(key, type, default_value, lo, hi)
#define RLE_GROUND_ATTITUDE_PARAM RLE_GROUND_PARAM
#define RLE_ATTITUDE_FILTER_PARAM RLE_GROUND_PARAM
#include "rle_vision/params/ground_params.def"
  RLE_CHECKED_ALL(GroundProjectorConfig);
  const AttitudeFilterOptions from_config = attitudeFilterFromConfig(defaults);
  EXPECT_EQ(from_config.smoothing, AttitudeFilterOptions().smoothing);
  EXPECT_EQ(from_config.max_rejected, AttitudeFilterOptions().max_rejected);
  EXPECT_EQ(groundFromConfig(defaults).camera_height_m, GroundOptions().camera_height_m);
}

TEST(ConfigDefaults, EdgeDetectorConfigMatchesCoreDefaults) {
  EXPECT_EQ(EdgeDetectorConfig::__getDefault__().edge_gain, LandmarkOptions().edge_gain);
  EXPECT_EQ(EdgeDetectorConfig::__getMin__().edge_gain, 0.05);
}

}  // namespace
}  // namespace rle_vision
