// The verifier at run time: the blobs of a class with a verifier are its candidates; each is
// scored (TrackedBlob::score) and only those scoring at least the class's min_score are kept.
// The cost is bounded by a per-frame cap on the candidates scored, largest first: a candidate
// beyond it is dropped unjudged and counted, so that a frame full of specks cannot stall the
// tracker. Verifiers are kept by class name, so a colour set swapped in at run time (learned
// ranges on color_ranges) keeps them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_table.h"
#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/verify/blob_verifier.h"

namespace rle_vision {

struct ClassVerifier {
  std::string class_name;
  std::shared_ptr<const BlobVerifier> model;
  double min_score = 0.5;
};

// The verifiers the classes name (ColorClass::verifier_path, else verifier_file), loaded. Throws std::runtime_error
// naming the class and the file when one cannot be read.
std::vector<ClassVerifier> loadClassVerifiers(const std::vector<ColorClass>& classes);

// The classes as the tracker segments them for `verifiers`: a floor_guard class already among
// them is dropped; then, when the field class comes before a class whose verifier keeps a floor
// guard (BlobVerifier::floorGuardScale over 1), a floor_guard class (the field's range grown by
// the largest such scale, scaledRange) goes just before the first such class, as the
// verifier's candidates were made in training. The guard only takes pixels: no region of it is
// ever a blob. Without a field class before them, with a wrapping field range or with no room
// left (kMaxColorClasses), the classes come back without a guard.
std::vector<ColorClass> withFloorGuard(std::vector<ColorClass> classes, const std::vector<ClassVerifier>& verifiers);

// The classes with `floor` (the frame's floor colour, the field stage's) as the field class, as
// a verifier's candidates were made in training (the floor's pixels the floor's first): in place
// of a field class's range, else just before the first class with a verifier, taking pixels but
// yielding no blob; with no class with a verifier, or no room, unchanged. For a lone image; a
// camera stream gets the field class from the colour learning loop.
std::vector<ColorClass> withFloorFirst(std::vector<ColorClass> classes, const ColorClass& floor);

struct ScreeningCounts {
  uint32_t candidates = 0;  // blobs of classes with a verifier
  uint32_t scored = 0;
  uint32_t rejected = 0;  // scored below min_score
  uint32_t over_cap = 0;  // not scored: beyond max_candidates_per_frame
  void add(const ScreeningCounts& o) {
    candidates += o.candidates;
    scored += o.scored;
    rejected += o.rejected;
    over_cap += o.over_cap;
  }
};

class CandidateScreen {
 public:
  CandidateScreen() = default;
  explicit CandidateScreen(std::vector<ClassVerifier> verifiers, uint32_t max_candidates_per_frame = 50)
      : verifiers_(std::move(verifiers)), max_candidates_(max_candidates_per_frame) {}

  bool empty() const { return verifiers_.empty(); }
  const std::vector<ClassVerifier>& verifiers() const { return verifiers_; }
  uint32_t maxCandidatesPerFrame() const { return max_candidates_; }
  // True when some blob is a candidate: only then does apply() need the frame.
  bool hasCandidates(const ColorTable& table, const std::vector<TrackedBlob>& blobs);

  // Scores the candidates among `blobs` on `bgr` (CV_8UC3, the frame the blobs were found in)
  // and removes those rejected or over the cap, keeping the order of the rest; `aligned` (may be
  // null) holds one value per blob and is kept in step.
  ScreeningCounts apply(const cv::Mat& bgr, const ColorTable& table, std::vector<TrackedBlob>* blobs,
                        std::vector<double>* aligned = nullptr);

 private:
  // verifiers_ index per table label (1 + class index), -1 for none; rebuilt when the table changes.
  const std::vector<int>& verifierOfLabel(const ColorTable& table);

  std::vector<ClassVerifier> verifiers_;
  uint32_t max_candidates_ = 50;
  const ColorTable* labels_table_ = nullptr;
  std::vector<std::string> labels_names_;
  std::vector<int> verifier_of_label_;
  std::vector<size_t> order_;
  std::vector<char> keep_;
  cv::Mat patch_bgr_, patch_yuv_;
};

}  // namespace rle_vision
