#include "rle_vision/verify/verifier_training.h"

#include <algorithm>

namespace rle_vision {

ColorClass widenedRange(ColorClass range, int levels) {
  for (int c = 0; c < 3; ++c) {
    range.min[c] = static_cast<uint8_t>(std::clamp(range.min[c] - levels, 0, 255));
    range.max[c] = static_cast<uint8_t>(std::clamp(range.max[c] + levels, 0, 255));
  }
  return range;
}

VerifierTrainingSet::VerifierTrainingSet(const ColorClass& candidate_range, uint32_t min_area_px)
    : table_({candidate_range}), min_area_px_(min_area_px) {}

void VerifierTrainingSet::addFrame(const cv::Mat& bgr, const std::vector<cv::Rect>& object_boxes) {
  segmenter_.segment(bgr, PixelFormat::BGR8, table_, &regions_);
  CandidateFeatures x;
  for (const Region& r : regions_) {
    if (r.area < min_area_px_) continue;
    candidateFeatures(bgr, r, &x);
    features_.push_back(cv::Mat(1, kCandidateFeatureCount, CV_32F, x.data()));
    bool on_object = false;
    for (const cv::Rect& b : object_boxes) {
      on_object = on_object || (r.cx >= b.x && r.cx <= b.br().x - 1 && r.cy >= b.y && r.cy <= b.br().y - 1);
    }
    labels_.push_back(on_object);
  }
}

void VerifierTrainingSet::append(const VerifierTrainingSet& other) {
  if (other.features_.empty()) return;
  features_.push_back(other.features_);
  labels_.insert(labels_.end(), other.labels_.begin(), other.labels_.end());
}

int VerifierTrainingSet::positives() const { return static_cast<int>(std::count(labels_.begin(), labels_.end(), 1)); }

}  // namespace rle_vision
