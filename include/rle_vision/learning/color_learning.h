// Colour ranges from landmarks (the paper's section VI and its open problem): the lines of an
// edge object bound a region; the colours inside it give a range; ranges of matching classes
// follow what the landmarks see, so the tracker keeps working as the light changes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/segment/segmenter.h"

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
// The same with a weight per pixel (nullptr: every pixel weighs 1), e.g. so that each of
// several examples counts once however large; `stats->pixels` counts pixels, not weight.
bool weightedColorStats(const std::vector<Channels>& pixels, const std::vector<double>* weights, ColorStats* stats,
                        double outlier_distance = 40, uint32_t large_object_px = 100, double small_object_margin = 15);

// The colour modes of a set of pixels (one space): from the densest colour, a mean shift
// within `radius` on every channel, its members taken out, and again, at most `max_modes`
// times. Modes smaller than `min_size` are dropped. Returns members as indices into `pixels`.
std::vector<std::vector<int>> colorModes(const std::vector<Channels>& pixels, double radius, size_t min_size,
                                         int max_modes = 4);

// The parameters (blend, match_gate, max_sigma, mode_radius, ...; learning_* in files and ROS)
// are the LEARNING group of landmark_params.def, with their defaults and meanings.
struct LearningOptions {
#define RLE_LEARNING_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
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

  // Why a measurement changed nothing.
  enum class Rejection {
    kNone,           // applied
    kTooSmall,       // the region holds fewer than min_region_px pixels
    kAboveHorizon,   // at or above the horizon: not an obstacle
    kMixedColours,   // a channel spreads more than max_sigma
    kBackground,     // the ground's or the sky's colour
    kNoClass,        // farther than match_gate from every class
    kNotInRange,     // most of its pixels lie outside the nearest class's current range (a
                     // colour beside the class, not the class drifting; nor a new class)
    kOverlapsGround, // the class's range would overlap the ground's colour
    kOverlapsSky,    // ... the sky's
    kOverlapsClass,  // ... another class's (conflicting_class)
    kTakesInBackground,  // the pixels the range would add lie mostly away from the measured objects
  };
  // What the last update saw, for tests and debug views: one colour mode of one region
  // bounded by lines, or (from_blob) one blob of a class.
  struct Measurement {
    std::vector<cv::Point2d> region;    // the region's outline (a blob's: its box)
    cv::Rect pixels_box;                // where the mode's pixels lie (a blob's box, without the ring)
    bool from_blob = false;
    ColorStats stats[kNumColorSpaces];  // per space used by the classes
    int matched_class = -1;             // -1: none
    Rejection rejection = Rejection::kNone;
    int conflicting_class = -1;         // with kOverlapsClass
    std::string rejected;               // the rejection in words ("" when it was applied)
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

  // Which colour spaces the classes (and class creation) use.
  struct Spaces {
    bool used[kNumColorSpaces] = {false, false, false};
  };
  // A region's pixels: positions and YUV colours.
  struct RegionPixels {
    std::vector<cv::Point> positions;
    std::vector<Channels> yuv;
  };

  Spaces usedSpaces() const;
  void measureBackground(const cv::Mat& bgr, const HorizonEstimate& horizon, const std::vector<cv::Rect>& objects,
                         const Spaces& spaces);
  bool regionPixels(const cv::Mat& bgr, const std::vector<cv::Point2d>& region, RegionPixels* pixels) const;
  void measureRegion(const cv::Mat& bgr, const std::vector<const DetectedLine*>& lines, const HorizonEstimate& horizon,
                     const Spaces& spaces, std::vector<std::vector<ColorStats>>* matched);
  void measureMode(const cv::Mat& bgr, const RegionPixels& pixels, const std::vector<int>& mode,
                   const HorizonEstimate& horizon, const Spaces& spaces, Measurement* m);
  void measureBlobs(const cv::Mat& bgr, const HorizonEstimate& horizon, std::vector<std::vector<ColorStats>>* matched);
  void measureBlob(const cv::Mat& bgr, const Region& region, const HorizonEstimate& horizon, Measurement* m,
                   std::vector<Channels>* pixels);
  void blobPixels(const cv::Mat& bgr, const Region& region, int k, std::vector<Channels>* pixels) const;
  int nearestClass(const Measurement& m) const;
  double distanceToClass(int k, const ColorStats& measured) const;
  bool mostlyInRange(int k, const std::vector<Channels>& colours) const;
  void applyMatched(const std::vector<std::vector<ColorStats>>& matched, double stamp_s);
  Rejection apply(int k, const ColorStats& measured, double stamp_s, int* conflicting_class);
  bool takesInBackground(int k, const ColorStats& blended);
  bool driftBack(double stamp_s);
  void createClasses(double stamp_s);
  void addClass(const Candidate& candidate, double stamp_s);
  bool updateClassSet();
  bool publishable(int k, Channels* lo, Channels* hi) const;
  bool isBackground(ColorSpace space, const ColorStats& stats) const;
  void reject(Measurement* m, Rejection why, int conflicting_class = -1) const;

  std::vector<ColorClass> configured_, classes_;
  std::vector<ClassState> state_;
  std::vector<Candidate> candidates_;
  LearningOptions options_;
  std::vector<Measurement> measurements_;
  bool have_ground_[kNumColorSpaces] = {false, false, false}, have_sky_[kNumColorSpaces] = {false, false, false};
  ColorStats ground_[kNumColorSpaces], sky_[kNumColorSpaces];
  // This update's frame (for the background gate, converted to a space when first needed) and,
  // per class, where its applied measurements lie (blobs with their ring, modes' pixels).
  const cv::Mat* frame_bgr_ = nullptr;
  cv::Mat frame_in_space_[kNumColorSpaces];
  std::vector<std::vector<cv::Rect>> measured_boxes_;
  int created_ = 0;
  // from_blobs: the current classes' blobs, segmented here as the tracker does.
  std::unique_ptr<ColorTable> blob_table_;  // built from classes_; null when they changed
  Segmenter blob_segmenter_;
  std::vector<Region> blob_regions_;
};

}  // namespace rle_vision
