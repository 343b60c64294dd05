#include "rle_vision/verify/candidate_screen.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "rle_vision/verify/verifier_training.h"

namespace rle_vision {

std::vector<ClassVerifier> loadClassVerifiers(const std::vector<ColorClass>& classes) {
  std::vector<ClassVerifier> verifiers;
  for (const ColorClass& c : classes) {
    if (c.verifier_file.empty()) continue;
    const std::string& path = c.verifier_path.empty() ? c.verifier_file : c.verifier_path;
    try {
      verifiers.push_back({c.name, std::make_shared<const BlobVerifier>(BlobVerifier::load(path)), c.min_score});
    } catch (const std::exception& e) {
      throw std::runtime_error("colour class '" + c.name + "': cannot load its verifier_file: " + e.what());
    }
  }
  return verifiers;
}

namespace {

// `range` as a class named `name` that takes its pixels from the classes after it but is never
// a blob itself (no region reaches its minimum area) and has no verifier.
ColorClass pixelsOnlyClass(ColorClass range, const char* name) {
  range.name = name;
  range.min_area_px = std::numeric_limits<uint32_t>::max();
  range.verifier_file.clear();
  range.verifier_path.clear();
  return range;
}

}  // namespace

std::vector<ColorClass> withFloorGuard(std::vector<ColorClass> classes, const std::vector<ClassVerifier>& verifiers) {
  classes.erase(std::remove_if(classes.begin(), classes.end(),
                               [](const ColorClass& c) { return c.name == kFloorGuardClassName; }),
                classes.end());
  const auto field = std::find_if(classes.begin(), classes.end(), [](const ColorClass& c) { return c.name == kFieldClassName; });
  if (field == classes.end() || static_cast<int>(classes.size()) >= kMaxColorClasses) return classes;
  for (int c = 0; c < 3; ++c) {
    if (field->min[c] > field->max[c]) return classes;  // a wrapping range cannot be grown as one box
  }
  auto scaleOf = [&](const ColorClass& c) {
    double scale = 1.0;
    for (const ClassVerifier& v : verifiers) scale = v.class_name == c.name ? v.model->floorGuardScale() : scale;
    return scale;
  };
  double scale = 1.0;
  auto first_guarded = classes.end();
  for (auto c = field + 1; c != classes.end(); ++c) {
    if (scaleOf(*c) <= 1.0) continue;
    if (first_guarded == classes.end()) first_guarded = c;
    scale = std::max(scale, scaleOf(*c));
  }
  if (first_guarded == classes.end()) return classes;
  classes.insert(first_guarded, pixelsOnlyClass(scaledRange(*field, scale), kFloorGuardClassName));
  return classes;
}

std::vector<ColorClass> withFloorFirst(std::vector<ColorClass> classes, const ColorClass& floor) {
  const auto verified = std::find_if(classes.begin(), classes.end(), [](const ColorClass& c) { return !c.verifier_file.empty(); });
  if (verified == classes.end()) return classes;
  for (ColorClass& c : classes) {
    if (c.name != kFieldClassName) continue;
    c.space = floor.space, c.min = floor.min, c.max = floor.max;
    return classes;
  }
  if (static_cast<int>(classes.size()) >= kMaxColorClasses) return classes;
  classes.insert(verified, pixelsOnlyClass(floor, kFieldClassName));
  return classes;
}

const std::vector<int>& CandidateScreen::verifierOfLabel(const ColorTable& table) {
  // The table is compared by its names too: a new table may reuse a freed one's address.
  bool same = labels_table_ == &table && labels_names_.size() == table.classes().size();
  for (size_t i = 0; same && i < labels_names_.size(); ++i) same = labels_names_[i] == table.classes()[i].name;
  if (same) return verifier_of_label_;
  labels_table_ = &table;
  labels_names_.clear();
  verifier_of_label_.assign(table.classes().size() + 1, -1);
  for (size_t i = 0; i < table.classes().size(); ++i) {
    labels_names_.push_back(table.classes()[i].name);
    for (size_t v = 0; v < verifiers_.size(); ++v) {
      if (verifiers_[v].class_name == table.classes()[i].name) verifier_of_label_[i + 1] = static_cast<int>(v);
    }
  }
  return verifier_of_label_;
}

bool CandidateScreen::hasCandidates(const ColorTable& table, const std::vector<TrackedBlob>& blobs) {
  if (verifiers_.empty()) return false;
  const std::vector<int>& verifier_of = verifierOfLabel(table);
  return std::any_of(blobs.begin(), blobs.end(), [&](const TrackedBlob& b) {
    return b.region.label < static_cast<int>(verifier_of.size()) && verifier_of[b.region.label] >= 0;
  });
}

ScreeningCounts CandidateScreen::apply(const cv::Mat& bgr, const ColorTable& table, std::vector<TrackedBlob>* blobs,
                                       std::vector<double>* aligned) {
  ScreeningCounts counts;
  if (verifiers_.empty() || blobs->empty()) return counts;
  if (bgr.type() != CV_8UC3) throw std::invalid_argument("the verifier needs the frame as 8-bit BGR (CV_8UC3)");
  const std::vector<int>& verifier_of = verifierOfLabel(table);
  auto verifierOf = [&](const TrackedBlob& b) {
    return b.region.label < static_cast<int>(verifier_of.size()) ? verifier_of[b.region.label] : -1;
  };
  order_.clear();
  for (size_t i = 0; i < blobs->size(); ++i) {
    if (verifierOf((*blobs)[i]) >= 0) order_.push_back(i);
  }
  counts.candidates = static_cast<uint32_t>(order_.size());
  // Largest first: under the cap, the specks go unjudged, not the objects.
  std::stable_sort(order_.begin(), order_.end(),
                   [&](size_t a, size_t b) { return (*blobs)[a].region.area > (*blobs)[b].region.area; });
  keep_.assign(blobs->size(), 1);
  CandidateFeatures x;
  const FrameChroma frame = order_.empty() ? FrameChroma() : frameChroma(bgr);
  for (size_t k = 0; k < order_.size(); ++k) {
    TrackedBlob& blob = (*blobs)[order_[k]];
    if (k >= max_candidates_) {
      keep_[order_[k]] = 0;
      ++counts.over_cap;
      continue;
    }
    const ClassVerifier& verifier = verifiers_[static_cast<size_t>(verifierOf(blob))];
    candidateFeatures(bgr, frame, blob.region, &x, &patch_bgr_, &patch_yuv_);
    blob.score = verifier.model->score(x);
    ++counts.scored;
    if (blob.score < verifier.min_score) {
      keep_[order_[k]] = 0;
      ++counts.rejected;
    }
  }
  size_t out = 0;
  for (size_t i = 0; i < blobs->size(); ++i) {
    if (!keep_[i]) continue;
    if (out != i) {
      (*blobs)[out] = std::move((*blobs)[i]);
      if (aligned) (*aligned)[out] = (*aligned)[i];
    }
    ++out;
  }
  blobs->resize(out);
  if (aligned) aligned->resize(out);
  return counts;
}

}  // namespace rle_vision
