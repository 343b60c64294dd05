// The live-tunable parameters start where the core's defaults are: a default changed in one
// place and not the other (or a parameter that never reaches the core) fails here.
#include <gtest/gtest.h>

#include "../../src/nodelets/conversions.h"
#include "rle_vision/EdgeDetectorConfig.h"
#include "rle_vision/GroundProjectorConfig.h"
#include "rle_vision/TrackerConfig.h"
#include "rle_vision/blob_tracker.h"
#include "rle_vision/segmenter.h"

namespace rle_vision {
namespace {

TEST(ConfigDefaults, LandmarkConfigMatchesCoreDefaults) {
  const LandmarkOptions from_config = optionsFromConfig(LandmarkConfig::__getDefault__());
  const LandmarkOptions core;
  EXPECT_EQ(from_config.objects.gray_threshold, core.objects.gray_threshold);
  EXPECT_EQ(from_config.objects.sharp_threshold, core.objects.sharp_threshold);
  EXPECT_EQ(from_config.objects.min_object_px, core.objects.min_object_px);
  EXPECT_EQ(from_config.objects.thin, core.objects.thin);
  EXPECT_EQ(from_config.hough.min_votes, core.hough.min_votes);
  EXPECT_EQ(from_config.hough.min_line_length_px, core.hough.min_line_length_px);
  EXPECT_EQ(from_config.hough.sampling_margin, core.hough.sampling_margin);
  EXPECT_EQ(from_config.hough.max_samples_per_object, core.hough.max_samples_per_object);
  EXPECT_EQ(from_config.hough.max_rounds, core.hough.max_rounds);
  EXPECT_EQ(from_config.hough.max_failed_peaks, core.hough.max_failed_peaks);
  EXPECT_EQ(from_config.hough.min_pair_distance_px, core.hough.min_pair_distance_px);
  EXPECT_EQ(from_config.hough.theta_bin_deg, core.hough.theta_bin_deg);
  EXPECT_EQ(from_config.hough.intercept_bin_px, core.hough.intercept_bin_px);
  EXPECT_EQ(from_config.hough.peak_angle_deg, core.hough.peak_angle_deg);
  EXPECT_EQ(from_config.hough.peak_distance_px, core.hough.peak_distance_px);
  EXPECT_EQ(from_config.hough.fit_distance_px, core.hough.fit_distance_px);
  EXPECT_EQ(from_config.hough.max_gap_px, core.hough.max_gap_px);
  EXPECT_EQ(from_config.hough.min_support_ratio, core.hough.min_support_ratio);
  EXPECT_EQ(from_config.hough.seed, core.hough.seed);
  EXPECT_EQ(from_config.horizon.min_piece_length_px, core.horizon.min_piece_length_px);
  EXPECT_EQ(from_config.horizon.max_angle_deg, core.horizon.max_angle_deg);
  EXPECT_EQ(from_config.horizon.merge_angle_deg, core.horizon.merge_angle_deg);
  EXPECT_EQ(from_config.horizon.merge_distance_px, core.horizon.merge_distance_px);
  EXPECT_EQ(from_config.horizon.min_coverage, core.horizon.min_coverage);
}

TEST(ConfigDefaults, LearningConfigMatchesCoreDefaults) {
  const LearningOptions from_config = learningFromConfig(LandmarkConfig::__getDefault__());
  const LearningOptions core;
  EXPECT_EQ(from_config.blend, core.blend);
  EXPECT_EQ(from_config.match_gate, core.match_gate);
  EXPECT_EQ(from_config.max_sigma, core.max_sigma);
  EXPECT_EQ(from_config.mode_radius, core.mode_radius);
  EXPECT_EQ(from_config.min_region_px, core.min_region_px);
  EXPECT_EQ(from_config.shrink_px, core.shrink_px);
  EXPECT_EQ(from_config.horizon_margin_px, core.horizon_margin_px);
  EXPECT_EQ(from_config.stale_after_s, core.stale_after_s);
  EXPECT_EQ(from_config.create_classes, core.create_classes);
  EXPECT_EQ(from_config.persist_frames, core.persist_frames);
  EXPECT_EQ(from_config.min_new_class_px, core.min_new_class_px);
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
  const TrackerConfig tracker = TrackerConfig::__getDefault__();
  const TrackerOptions tracking;
  const SegmenterOptions segmenting;
  EXPECT_EQ(tracker.connectivity, static_cast<int>(segmenting.connectivity));
  EXPECT_EQ(static_cast<uint32_t>(tracker.min_area_px), segmenting.min_area_px);
  EXPECT_EQ(tracker.tracking_gate_px, tracking.gate_px);
  EXPECT_EQ(tracker.max_area_ratio, tracking.max_area_ratio);
  EXPECT_EQ(tracker.max_missed_frames, tracking.max_missed_frames);
  EXPECT_EQ(tracker.velocity_smoothing, tracking.velocity_smoothing);
}

}  // namespace
}  // namespace rle_vision
