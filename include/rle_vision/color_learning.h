// Colour ranges from landmarks (the paper's section VI and its open problem): the lines of an
// edge object bound a region; the colours inside it give a range; ranges of matching classes
// follow what the landmarks see, so the tracker keeps working as the light changes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color_class.h"
#include "rle_vision/landmark_detector.h"

namespace rle_vision {

// The region an edge object's lines bound: the convex hull of their end points and of the
// points where pairs of them meet (near both segments). Empty when fewer than 2 lines.
std::vector<cv::Point2d> regionFromLines(const std::vector<const DetectedLine*>& lines);

struct ColorStats {
  Channels lo{{0, 0, 0}}, hi{{255, 255, 255}};  // the range
  double mean[3] = {0, 0, 0};
  double sigma[3] = {0, 0, 0};
  uint32_t pixels = 0;  // after outlier removal
};

// The paper's statistics on pixels of one space: the mean per channel; pixels more than
// `outlier_distance` from it on any channel dropped; then mean +- 3 sigma when more than
// `large_object_px` pixels remain, else mean +- `small_object_margin`. False without pixels.
bool colorStats(const std::vector<Channels>& pixels, ColorStats* stats, double outlier_distance = 40,
                uint32_t large_object_px = 100, double small_object_margin = 15);

// The colour modes of a set of pixels (one space): from the densest colour, a mean shift
// within `radius` on every channel, its members taken out, and again, at most `max_modes`
// times. Modes smaller than `min_size` are dropped. Returns members as indices into `pixels`.
std::vector<std::vector<int>> colorModes(const std::vector<Channels>& pixels, double radius, size_t min_size,
                                         int max_modes = 4);

struct LearningOptions {
  double blend = 0.2;               // weight of a new measurement in a class's range (0..1]
  double mode_radius = 20;          // a colour mode holds the pixels this close (every channel) to its mean
  double match_gate = 45;           // largest distance between a class's centre and a measurement's mean
  double max_sigma = 25;            // a measurement spreading more than this on a channel is mixed colours
  uint32_t min_region_px = 60;      // smaller regions are not measured
  double shrink_px = 2;             // the region is eroded by this much (edge pixels mix colours)
  double horizon_margin_px = 3;     // regions within this of the horizon (or above it) are not obstacles
  double stale_after_s = 5;         // a class not measured for this long drifts back to its configured range
  bool create_classes = false;      // unmatched, persistent large regions become classes learned_N
  int persist_frames = 15;          // frames an unmatched colour must be seen to become a class
  uint32_t min_new_class_px = 400;  // and its size
};

// Reason the options are unusable, or "" when they are fine.
std::string validateLearningOptions(const LearningOptions& options);

// Follows the configured classes with what the landmarks measure. Not thread-safe.
class ColorLearner {
 public:
  ColorLearner(std::vector<ColorClass> configured, const LearningOptions& options);
  void setOptions(const LearningOptions& options) { options_ = options; }

  // One frame: its BGR image and the landmark result computed on it (lines, horizon, objects).
  // Returns true when the classes changed (classes() then holds the set to publish).
  bool update(const cv::Mat& bgr, const LandmarkResult& landmarks, const EdgeObjectFinder& objects, double stamp_s);

  // Continues from ranges learned earlier (a restarted node resuming from what the tracker still
  // uses): each configured class with a "learned" class of the same name and space in `learned`
  // takes that range as its current one. Returns how many classes resumed.
  int resume(const std::vector<ColorClass>& learned, double stamp_s);

  // The current classes: configured ones with their learned ranges (source "learned" once
  // measured), then any created classes.
  const std::vector<ColorClass>& classes() const { return classes_; }

  // What the last update saw, for tests and debug views.
  // One colour mode of one region.
  struct Measurement {
    std::vector<cv::Point2d> region;
    cv::Rect pixels_box;                // where the mode's pixels lie
    ColorStats stats[kNumColorSpaces];  // per space used by the classes
    int matched_class = -1;             // -1: none
    std::string rejected;               // why it changed nothing ("" when it was applied)
  };
  const std::vector<Measurement>& lastMeasurements() const { return measurements_; }
  // The ground (below the horizon) and sky (above it) measured in the last update, per space.
  const ColorStats* groundStats(ColorSpace space) const;
  const ColorStats* skyStats(ColorSpace space) const;

 private:
  struct ClassState {
    double lo[3], hi[3];  // the smoothed range (wrapped ranges are not learned)
    double last_measured_s = -1;
  };
  struct Candidate {
    double mean[3];
    ColorStats stats;
    int frames = 0;
    double last_seen_s = 0;
  };

  void measureBackground(const cv::Mat& bgr, const HorizonEstimate& horizon, const std::vector<cv::Rect>& objects,
                         const bool* used_spaces);
  bool apply(int k, const ColorStats& measured, double stamp_s, std::string* rejected);
  bool driftBack(double stamp_s);
  bool publishable(int k, Channels* lo, Channels* hi) const;

  std::vector<ColorClass> configured_, classes_;
  std::vector<ClassState> state_;
  std::vector<Candidate> candidates_;
  LearningOptions options_;
  std::vector<Measurement> measurements_;
  bool have_ground_[kNumColorSpaces] = {false, false, false}, have_sky_[kNumColorSpaces] = {false, false, false};
  ColorStats ground_[kNumColorSpaces], sky_[kNumColorSpaces];
  int created_ = 0;
};

}  // namespace rle_vision
