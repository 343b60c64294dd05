// A verifier learned from labelled frames: colour proposes candidates (the tracker's blobs of a
// permissive range), a small model decides which candidates are the object. The model is
// OpenCV's ml Boost (Real AdaBoost on depth-2 trees): deterministic, small (a few tens of KB),
// microseconds a candidate. Trained across groups (recordings in different halls and light), it
// is one model per group, each trained without that group, and a candidate's score is their
// mean: what only one hall's frames taught (a colour, a background) weighs in one model of
// several.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/verify/boosted_trees.h"  // also declares cv::ml::Boost
#include "rle_vision/verify/candidate_features.h"

namespace rle_vision {

struct VerifierTrainOptions {
  int weak_count = 100;   // boosted trees
  int max_depth = 2;      // of each tree
  // Negatives usually outnumber positives many times: each class's samples are weighted so that
  // both classes weigh the same in training.
  bool balance_classes = true;
};

// The distinct groups among `group` (one per candidate), in increasing order.
std::vector<int> distinctGroups(const std::vector<int>& group);
// The candidates of every group but `held`: their feature rows, labels and (`row_groups`, may
// be null) groups. False when they do not hold both an object and a non-object, so that no
// model can be trained on them.
bool rowsWithoutGroup(const cv::Mat& features, const std::vector<int>& is_object, const std::vector<int>& group, int held,
                      cv::Mat* rows, std::vector<int>* labels, std::vector<int>* row_groups = nullptr);

class BlobVerifier {
 public:
  BlobVerifier();
  ~BlobVerifier();
  BlobVerifier(BlobVerifier&&) noexcept;
  BlobVerifier& operator=(BlobVerifier&&) noexcept;

  // `features`: one row per candidate (CV_32F, kCandidateFeatureCount columns); `is_object`: 1
  // for candidates on a labelled object, 0 for the others. Throws std::invalid_argument when
  // either class has no sample or the sizes disagree.
  static BlobVerifier train(const cv::Mat& features, const std::vector<int>& is_object,
                            const VerifierTrainOptions& options = VerifierTrainOptions());
  // `group[i]`: candidate i's group (its recording, its date). With two or more groups, one
  // model per group, trained on the other groups' candidates (a group whose others hold no
  // object, or nothing else, adds no model); with fewer, or when no group adds one, train().
  // Throws as train() does.
  static BlobVerifier trainAcrossGroups(const cv::Mat& features, const std::vector<int>& is_object,
                                        const std::vector<int>& group,
                                        const VerifierTrainOptions& options = VerifierTrainOptions());

  bool trained() const;
  int modelCount() const { return static_cast<int>(models_.size()); }
  // The candidate's score in [0, 1]: the logistic of the models' mean boosted sum (each sum half
  // a log-odds: 0.5 is the decision boundary); 0 without a model.
  float score(const CandidateFeatures& features) const;

  // The permissive colour range whose blobs are the candidates (kept in the model file: the
  // verifier was trained on that range's blobs and judges them only).
  void setCandidateRange(const ColorClass& range) { candidate_range_ = range; }
  const ColorClass& candidateRange() const { return candidate_range_; }
  // The floor guard's scale its candidates were made with (1: none, as in files made before
  // it): at run time the floor's range grown by it (scaledRange) takes its pixels before the
  // candidates' range does (withFloorGuard, verify/candidate_screen.h).
  void setFloorGuardScale(double scale) { floor_guard_scale_ = scale; }
  double floorGuardScale() const { return floor_guard_scale_; }

  // The models and the candidate range as a YAML or XML file (OpenCV FileStorage; a name
  // ending in .gz is compressed), with the feature count and version checked on load. Both throw
  // std::runtime_error with the path and the reason. `note` (how the model was made) goes at
  // the top of the file as comment lines.
  void save(const std::string& path, const std::string& note = "") const;
  static BlobVerifier load(const std::string& path);

 private:
  void addModel(const cv::Ptr<cv::ml::Boost>& model);

  std::vector<cv::Ptr<cv::ml::Boost>> models_;
  std::vector<BoostedTrees> flat_models_;  // the same models, scored without OpenCV's overhead
  ColorClass candidate_range_;
  double floor_guard_scale_ = 1.0;
};

}  // namespace rle_vision
