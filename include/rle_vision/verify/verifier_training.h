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

class VerifierTrainingSet {
 public:
  explicit VerifierTrainingSet(const ColorClass& candidate_range, uint32_t min_area_px = 20);

  // Every candidate of `bgr` (CV_8UC3) with its label.
  void addFrame(const cv::Mat& bgr, const std::vector<cv::Rect>& object_boxes);
  // Appends another set's candidates (the same range).
  void append(const VerifierTrainingSet& other);

  const cv::Mat& features() const { return features_; }  // CV_32F, one row per candidate
  const std::vector<int>& labels() const { return labels_; }
  int positives() const;

 private:
  ColorTable table_;
  uint32_t min_area_px_;
  Segmenter segmenter_;
  std::vector<Region> regions_;
  cv::Mat features_;
  std::vector<int> labels_;
};

}  // namespace rle_vision
