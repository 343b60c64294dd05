#include "rle_vision/verify/verifier_training.h"

#include <algorithm>
#include <stdexcept>

namespace rle_vision {

ColorClass widenedRange(ColorClass range, int levels) {
  for (int c = 0; c < 3; ++c) {
    range.min[c] = static_cast<uint8_t>(std::clamp(range.min[c] - levels, 0, 255));
    range.max[c] = static_cast<uint8_t>(std::clamp(range.max[c] + levels, 0, 255));
  }
  return range;
}

ColorClass rangeCovering(const std::vector<ColorClass>& ranges) {
  if (ranges.empty()) throw std::invalid_argument("no range to cover");
  ColorClass covering = ranges.front();
  for (const ColorClass& r : ranges) {
    if (r.space != covering.space) throw std::invalid_argument("ranges in different colour spaces cannot be covered by one");
    for (int c = 0; c < 3; ++c) {
      if (r.min[c] > r.max[c]) throw std::invalid_argument("a wrapping range cannot be covered");
      covering.min[c] = std::min(covering.min[c], r.min[c]);
      covering.max[c] = std::max(covering.max[c], r.max[c]);
    }
  }
  return covering;
}

VerifierTrainingSet::VerifierTrainingSet(const ColorClass& candidate_range, uint32_t min_area_px)
    : range_(candidate_range), min_area_px_(min_area_px) {
  ColorTable check({candidate_range});  // throws now, with the reason, for an invalid range
}

void candidateRegions(Segmenter* segmenter, const cv::Mat& bgr, const ColorClass& range, const ColorClass* floor,
                      uint32_t min_area_px, std::vector<Region>* candidates) {
  const int label = floor ? 2 : 1;
  segmenter->segment(bgr, PixelFormat::BGR8, floor ? ColorTable({*floor, range}) : ColorTable({range}), candidates);
  candidates->erase(std::remove_if(candidates->begin(), candidates->end(),
                                   [&](const Region& r) { return r.label != label || r.area < min_area_px; }),
                    candidates->end());
}

void VerifierTrainingSet::addFrame(const cv::Mat& bgr, const std::vector<cv::Rect>& object_boxes,
                                   const ColorClass* floor) {
  candidateRegions(&segmenter_, bgr, range_, floor, min_area_px_, &regions_);
  CandidateFeatures x;
  const FrameChroma frame = regions_.empty() ? FrameChroma() : frameChroma(bgr);
  for (const Region& r : regions_) {
    candidateFeatures(bgr, frame, r, &x);
    features_.push_back(cv::Mat(1, kCandidateFeatureCount, CV_32F, x.data()));
    bool on_object = false;
    for (const cv::Rect& b : object_boxes) {
      on_object = on_object || (r.cx >= b.x && r.cx <= b.br().x - 1 && r.cy >= b.y && r.cy <= b.br().y - 1);
    }
    labels_.push_back(on_object);
    groups_.push_back(group_);
  }
}

void VerifierTrainingSet::append(const VerifierTrainingSet& other) {
  if (other.features_.empty()) return;
  features_.push_back(other.features_);
  labels_.insert(labels_.end(), other.labels_.begin(), other.labels_.end());
  groups_.insert(groups_.end(), other.groups_.begin(), other.groups_.end());
}

int VerifierTrainingSet::positives() const { return static_cast<int>(std::count(labels_.begin(), labels_.end(), 1)); }

}  // namespace rle_vision
