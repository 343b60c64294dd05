// What a verifier is trained on: the candidates of labelled frames (the blobs of a permissive
// colour range, exactly as the tracker will propose them at run time), each labelled by whether
// its centroid lies inside a labelled box of the object.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/segment/segmenter.h"
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

class VerifierTrainingSet {
 public:
  explicit VerifierTrainingSet(const ColorClass& candidate_range, uint32_t min_area_px = 20);

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

 private:
  ColorClass range_;
  uint32_t min_area_px_;
  Segmenter segmenter_;
  std::vector<Region> regions_;
  cv::Mat features_;
  std::vector<int> labels_;
  std::vector<int> groups_;
  int group_ = 0;
};

}  // namespace rle_vision
