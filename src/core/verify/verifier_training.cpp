#include "rle_vision/verify/verifier_training.h"

#include <algorithm>
#include <cmath>
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

ColorClass scaledRange(ColorClass range, double scale) {
  if (!(scale >= 1.0 && scale <= 16.0)) throw std::invalid_argument("a range's scale is 1..16");
  for (int c = 0; c < 3; ++c) {
    if (range.min[c] > range.max[c]) throw std::invalid_argument("a wrapping range cannot be scaled as one box");
    const double centre = 0.5 * (range.min[c] + range.max[c]), half = 0.5 * (range.max[c] - range.min[c]) * scale;
    range.min[c] = static_cast<uint8_t>(std::clamp<long>(std::lround(std::floor(centre - half)), 0, 255));
    range.max[c] = static_cast<uint8_t>(std::clamp<long>(std::lround(std::ceil(centre + half)), 0, 255));
  }
  return range;
}

const std::vector<double>& floorGuardScalesTried() {
  static const std::vector<double> scales = {1.0, 1.5, 2.0, 2.5, 3.0};
  return scales;
}

VerifierTrainingSet::VerifierTrainingSet(const ColorClass& candidate_range, uint32_t min_area_px,
                                         double floor_guard_scale)
    : range_(candidate_range), min_area_px_(min_area_px), floor_guard_scale_(floor_guard_scale) {
  ColorTable check({candidate_range});  // throws now, with the reason, for an invalid range
  if (!(floor_guard_scale >= 1.0 && floor_guard_scale <= 16.0)) throw std::invalid_argument("the floor guard's scale is 1..16");
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
  const ColorClass guarded_floor = floor ? scaledRange(*floor, floor_guard_scale_) : ColorClass();
  candidateRegions(&segmenter_, bgr, range_, floor ? &guarded_floor : nullptr, min_area_px_, &regions_);
  if (objects_by_group_.empty() || objects_by_group_.back().first != group_) objects_by_group_.emplace_back(group_, 0);
  objects_by_group_.back().second += static_cast<int>(object_boxes.size());
  CandidateFeatures x;
  const FrameChroma frame = regions_.empty() ? FrameChroma() : frameChroma(bgr);
  for (const Region& r : regions_) {
    candidateFeatures(bgr, frame, r, &x);
    features_.push_back(cv::Mat(1, kCandidateFeatureCount, CV_32F, x.data()));
    int object = -1;
    for (size_t k = 0; k < object_boxes.size() && object < 0; ++k) {
      const cv::Rect& b = object_boxes[k];
      if (r.cx >= b.x && r.cx <= b.br().x - 1 && r.cy >= b.y && r.cy <= b.br().y - 1) object = objects_ + static_cast<int>(k);
    }
    labels_.push_back(object >= 0);
    object_of_.push_back(object);
    groups_.push_back(group_);
  }
  objects_ += static_cast<int>(object_boxes.size());
}

int VerifierTrainingSet::objectsInGroup(int group) const {
  int objects = 0;
  for (const auto& g : objects_by_group_) objects += g.first == group ? g.second : 0;
  return objects;
}

void VerifierTrainingSet::append(const VerifierTrainingSet& other) {
  if (other.features_.empty()) return;
  features_.push_back(other.features_);
  labels_.insert(labels_.end(), other.labels_.begin(), other.labels_.end());
  groups_.insert(groups_.end(), other.groups_.begin(), other.groups_.end());
  for (int object : other.object_of_) object_of_.push_back(object < 0 ? -1 : objects_ + object);
  objects_ += other.objects_;
  objects_by_group_.insert(objects_by_group_.end(), other.objects_by_group_.begin(), other.objects_by_group_.end());
}

std::vector<HeldOutCounts> crossValidateByGroup(const VerifierTrainingSet& set, float min_score,
                                                const VerifierTrainOptions& options) {
  const std::vector<int> groups = distinctGroups(set.groups());
  std::vector<HeldOutCounts> counts;
  for (size_t g = 0; groups.size() >= 2 && g < groups.size(); ++g) {
    cv::Mat rows;
    std::vector<int> labels, row_groups;
    if (!rowsWithoutGroup(set.features(), set.labels(), set.groups(), groups[g], &rows, &labels, &row_groups)) continue;
    const BlobVerifier verifier = BlobVerifier::trainAcrossGroups(rows, labels, row_groups, options);
    HeldOutCounts held;
    held.group = groups[g];
    held.objects = set.objectsInGroup(groups[g]);
    std::vector<int> found;
    CandidateFeatures x;
    for (int i = 0; i < set.features().rows; ++i) {
      if (set.groups()[i] != groups[g]) continue;
      std::copy_n(set.features().ptr<float>(i), kCandidateFeatureCount, x.begin());
      if (verifier.score(x) < min_score) continue;
      ++held.kept;
      held.kept_on_object += set.labels()[i];
      if (set.objectOf()[i] >= 0) found.push_back(set.objectOf()[i]);
    }
    std::sort(found.begin(), found.end());
    held.found = static_cast<int>(std::unique(found.begin(), found.end()) - found.begin());
    counts.push_back(held);
  }
  return counts;
}

double chooseFloorGuardScale(const std::vector<VerifierTrainingSet>& sets, std::vector<double>* mean_f1) {
  if (sets.empty()) throw std::invalid_argument("no candidates to choose the floor guard's scale on");
  int best = 0;
  double best_f1 = -1;
  if (mean_f1) mean_f1->clear();
  for (size_t k = 0; k < sets.size(); ++k) {
    const std::vector<HeldOutCounts> held = crossValidateByGroup(sets[k]);
    double f1 = 0;
    for (const HeldOutCounts& h : held) f1 += h.f1() / held.size();
    if (mean_f1) mean_f1->push_back(held.empty() ? 0 : f1);
    const bool smaller_on_tie = f1 > best_f1 || (f1 == best_f1 && sets[k].floorGuardScale() < sets[best].floorGuardScale());
    if (!held.empty() && smaller_on_tie) best_f1 = f1, best = static_cast<int>(k);
  }
  return sets[best].floorGuardScale();
}

int VerifierTrainingSet::positives() const { return static_cast<int>(std::count(labels_.begin(), labels_.end(), 1)); }

}  // namespace rle_vision
