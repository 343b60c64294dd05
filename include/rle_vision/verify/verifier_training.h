// What a verifier is trained on: the candidates of labelled frames (the blobs of a permissive
// colour range, exactly as the tracker will propose them at run time), each labelled by whether
// its centroid lies inside a labelled box of the object.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/verify/blob_verifier.h"
#include "rle_vision/verify/candidate_features.h"

namespace rle_vision {

// `range` widened by `levels` on both sides of every channel (clamped to 0..255): candidates for
// recall, the verifier decides.
ColorClass widenedRange(ColorClass range, int levels);
// The smallest range holding every one of `ranges` (the object calibrated in each hall: the
// candidates must hold it in all of them). Throws std::invalid_argument when there are none,
// their colour spaces differ or one wraps.
ColorClass rangeCovering(const std::vector<ColorClass>& ranges);

// The candidates of `bgr` (CV_8UC3): the blobs of `range` of at least `min_area_px`. With
// `floor` (the frame's field colour) the floor's pixels are the floor's first, as in the tracker,
// where the field class comes before a class with a verifier: a permissive range then cannot
// run over the floor and swallow what lies on it.
void candidateRegions(Segmenter* segmenter, const cv::Mat& bgr, const ColorClass& range, const ColorClass* floor,
                      uint32_t min_area_px, std::vector<Region>* candidates);

// `range` grown about its centre: each channel's half width times `scale` (>= 1; clamped to
// 0..255). For a range of a robust spread (the floor's: median +- k sigma) it is the same range
// at scale x k sigma, whatever the hall's noise.
ColorClass scaledRange(ColorClass range, double scale);

// The floor guard's scales rle_vision_train tries: the floor's range grown by one of them takes
// its pixels before the candidates' range does (in the tracker, the floor_guard class), so the
// floor's outer pixels (a vignetted edge, a line's fringe) are not the start of a candidate that
// runs on into a ball. 1: no guard.
const std::vector<double>& floorGuardScalesTried();

class VerifierTrainingSet {
 public:
  // `floor_guard_scale`: the floor's range given to addFrame() is grown by it first
  // (scaledRange; 1: as it is).
  explicit VerifierTrainingSet(const ColorClass& candidate_range, uint32_t min_area_px = 20,
                               double floor_guard_scale = 1.0);

  // Every candidate of `bgr` (candidateRegions()) with its label.
  void addFrame(const cv::Mat& bgr, const std::vector<cv::Rect>& object_boxes, const ColorClass* floor = nullptr);
  // Appends another set's candidates (the same range), with their groups.
  void append(const VerifierTrainingSet& other);
  // The group (recording, date) of the candidates added from now on (0 at first).
  void setGroup(int group) { group_ = group; }

  const cv::Mat& features() const { return features_; }  // CV_32F, one row per candidate
  const std::vector<int>& labels() const { return labels_; }
  int positives() const;
  const std::vector<int>& groups() const { return groups_; }  // one per candidate
  // Per candidate, the object (numbered across frames from 0) its centroid lies on, or -1.
  const std::vector<int>& objectOf() const { return object_of_; }
  // The labelled objects of each group's frames, found by a candidate or not.
  int objectsInGroup(int group) const;
  double floorGuardScale() const { return floor_guard_scale_; }

 private:
  ColorClass range_;
  uint32_t min_area_px_;
  double floor_guard_scale_;
  Segmenter segmenter_;
  std::vector<Region> regions_;
  cv::Mat features_;
  std::vector<int> labels_;
  std::vector<int> groups_;
  std::vector<int> object_of_;
  std::vector<std::pair<int, int>> objects_by_group_;  // (group, labelled objects)
  int objects_ = 0;
  int group_ = 0;
};

// One group held out: its labelled objects, those found (a kept candidate's centroid on them),
// the candidates kept and those of them on an object.
struct HeldOutCounts {
  int group = 0, objects = 0, found = 0, kept = 0, kept_on_object = 0;
  double recall() const { return objects ? static_cast<double>(found) / objects : 0; }
  double precision() const { return kept ? static_cast<double>(kept_on_object) / kept : 1; }
  double f1() const { return recall() + precision() > 0 ? 2 * recall() * precision() / (recall() + precision()) : 0; }
};

// Grouped cross-validation of `set`: each group held out in turn, a verifier trained across the
// others (BlobVerifier::trainAcrossGroups) keeps its candidates scoring `min_score` or more. One
// entry per group (in group order) whose others hold both positives and negatives.
std::vector<HeldOutCounts> crossValidateByGroup(const VerifierTrainingSet& set, float min_score = 0.5f,
                                                const VerifierTrainOptions& options = VerifierTrainOptions());

// The floor guard's scale to train with, chosen on `sets` (the same frames' candidates, one set
// per scale tried) by their grouped cross-validation: the best mean F1 of recall and precision
// over the held-out groups (the smaller scale on a tie). `mean_f1` (may be null) gets each
// set's. With fewer than two groups nothing can be held out: the first set's scale.
double chooseFloorGuardScale(const std::vector<VerifierTrainingSet>& sets, std::vector<double>* mean_f1 = nullptr);

}  // namespace rle_vision
