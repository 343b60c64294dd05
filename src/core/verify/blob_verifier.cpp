#include "rle_vision/verify/blob_verifier.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/ml.hpp>

namespace rle_vision {

BlobVerifier::BlobVerifier() = default;
BlobVerifier::~BlobVerifier() = default;
BlobVerifier::BlobVerifier(BlobVerifier&&) noexcept = default;
BlobVerifier& BlobVerifier::operator=(BlobVerifier&&) noexcept = default;

namespace {

cv::Ptr<cv::ml::Boost> trainModel(const cv::Mat& features, const std::vector<int>& is_object,
                                  const VerifierTrainOptions& options) {
  if (features.type() != CV_32F || features.cols != kCandidateFeatureCount ||
      features.rows != static_cast<int>(is_object.size())) {
    throw std::invalid_argument("verifier training: features must be CV_32F, one row of " +
                                std::to_string(kCandidateFeatureCount) + " per candidate label");
  }
  int positives = 0;
  for (int label : is_object) positives += label != 0;
  const int negatives = static_cast<int>(is_object.size()) - positives;
  if (positives == 0 || negatives == 0) {
    throw std::invalid_argument("verifier training needs candidates on objects and off them (got " +
                                std::to_string(positives) + " on, " + std::to_string(negatives) + " off)");
  }
  cv::Mat responses(static_cast<int>(is_object.size()), 1, CV_32S);
  cv::Mat weights(static_cast<int>(is_object.size()), 1, CV_32F);
  for (size_t i = 0; i < is_object.size(); ++i) {
    responses.at<int>(static_cast<int>(i)) = is_object[i] ? 1 : 0;
    weights.at<float>(static_cast<int>(i)) =
        options.balance_classes ? 0.5f / (is_object[i] ? positives : negatives) * is_object.size() : 1.0f;
  }
  cv::Ptr<cv::ml::Boost> model = cv::ml::Boost::create();
  model->setBoostType(cv::ml::Boost::REAL);
  model->setWeakCount(options.weak_count);
  model->setMaxDepth(options.max_depth);
  model->setWeightTrimRate(0);  // every sample in every round: the same model every time
  model->setUseSurrogates(false);
  model->train(cv::ml::TrainData::create(features, cv::ml::ROW_SAMPLE, responses, cv::noArray(), cv::noArray(), weights));
  return model;
}

// Training makes models on every feature, all ordered (BoostedTrees relies on it): var_idx, when
// written, is 0, 1, ..., and every var_type but the response's (the last) is ordered.
bool everyVariableOrdered(const cv::FileNode& model) {
  std::vector<int> var_type, var_idx;
  model["var_type"] >> var_type;
  model["var_idx"] >> var_idx;
  if (var_type.empty() || !std::all_of(var_type.begin(), var_type.end() - 1, [](int t) { return t == cv::ml::VAR_ORDERED; })) {
    return false;
  }
  for (size_t i = 0; i < var_idx.size(); ++i) {
    if (var_idx[i] != static_cast<int>(i)) return false;
  }
  return true;
}

}  // namespace

BlobVerifier BlobVerifier::train(const cv::Mat& features, const std::vector<int>& is_object,
                                 const VerifierTrainOptions& options) {
  BlobVerifier verifier;
  verifier.addModel(trainModel(features, is_object, options));
  return verifier;
}

std::vector<int> distinctGroups(const std::vector<int>& group) {
  std::vector<int> groups(group);
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  return groups;
}

bool rowsWithoutGroup(const cv::Mat& features, const std::vector<int>& is_object, const std::vector<int>& group, int held,
                      cv::Mat* rows, std::vector<int>* labels, std::vector<int>* row_groups) {
  int positives = 0;
  for (size_t i = 0; i < group.size(); ++i) {
    if (group[i] == held) continue;
    rows->push_back(features.row(static_cast<int>(i)));
    labels->push_back(is_object[i]);
    if (row_groups) row_groups->push_back(group[i]);
    positives += is_object[i] != 0;
  }
  return positives > 0 && positives < static_cast<int>(labels->size());
}

BlobVerifier BlobVerifier::trainAcrossGroups(const cv::Mat& features, const std::vector<int>& is_object,
                                             const std::vector<int>& group, const VerifierTrainOptions& options) {
  if (group.size() != is_object.size() || features.rows != static_cast<int>(is_object.size())) {
    throw std::invalid_argument("verifier training: one feature row and one group per candidate label");
  }
  const std::vector<int> groups = distinctGroups(group);
  BlobVerifier verifier;
  for (size_t g = 0; groups.size() >= 2 && g < groups.size(); ++g) {
    cv::Mat rows;
    std::vector<int> labels;
    if (rowsWithoutGroup(features, is_object, group, groups[g], &rows, &labels)) {
      verifier.addModel(trainModel(rows, labels, options));
    }
  }
  if (verifier.models_.empty()) return train(features, is_object, options);
  return verifier;
}

void BlobVerifier::addModel(const cv::Ptr<cv::ml::Boost>& model) {
  models_.push_back(model);
  flat_models_.emplace_back(*model);
}

bool BlobVerifier::trained() const {
  return !models_.empty() && std::all_of(models_.begin(), models_.end(), [](const auto& m) { return m && m->isTrained(); });
}

float BlobVerifier::score(const CandidateFeatures& features) const {
  if (!trained()) return 0.0f;
  const cv::Mat row(1, kCandidateFeatureCount, CV_32F, const_cast<float*>(features.data()));
  // Real AdaBoost's sum estimates half the log-odds of the object class: the models' mean sum
  // (each trained without one group) gives the score.
  float total = 0;
  // OpenCV reads FLT_MAX as a missing value its own way (the features never hold it).
  const bool missing = std::find(features.begin(), features.end(), FLT_MAX) != features.end();
  for (size_t i = 0; i < models_.size(); ++i) {
    total += flat_models_[i].usable() && !missing ? flat_models_[i].sum(features.data())
                                                  : models_[i]->predict(row, cv::noArray(), cv::ml::DTrees::PREDICT_SUM);
  }
  return 1.0f / (1.0f + std::exp(-2.0f * total / static_cast<float>(models_.size())));
}

void BlobVerifier::save(const std::string& path, const std::string& note) const {
  if (!trained()) throw std::runtime_error(path + ": no trained verifier to save");
  cv::FileStorage file(path, cv::FileStorage::WRITE);
  if (!file.isOpened()) throw std::runtime_error(path + ": cannot write the verifier file");
  std::istringstream lines(note);
  for (std::string line; std::getline(lines, line);) file.writeComment(line);
  file << "rle_vision_verifier" << "{";
  file << "feature_count" << kCandidateFeatureCount;
  file << "feature_version" << kCandidateFeatureVersion;
  const ColorClass& c = candidate_range_;
  file << "candidate_range" << "{" << "name" << c.name << "space" << toString(c.space) << "min"
       << std::vector<int>{c.min[0], c.min[1], c.min[2]} << "max" << std::vector<int>{c.max[0], c.max[1], c.max[2]}
       << "min_area_px" << static_cast<int>(c.min_area_px) << "}";
  file << "floor_guard_scale" << floor_guard_scale_;
  file << "models" << "[";
  for (const auto& model : models_) {
    file << "{";
    model->write(file);
    file << "}";
  }
  file << "]" << "}";
}

BlobVerifier BlobVerifier::load(const std::string& path) {
  if (!std::ifstream(path).good()) throw std::runtime_error(path + ": cannot read the verifier file (missing or unreadable)");
  cv::FileStorage file;
  try {
    file.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": not a verifier file (" + e.msg + ")");
  }
  if (!file.isOpened()) throw std::runtime_error(path + ": cannot read the verifier file");
  const cv::FileNode root = file["rle_vision_verifier"];
  if (root.empty() || (root["models"].empty() && root["model"].empty())) throw std::runtime_error(path + ": not a verifier file (rle_vision_train writes them)");
  if (static_cast<int>(root["feature_count"]) != kCandidateFeatureCount) {
    throw std::runtime_error(path + ": made for " + std::to_string(static_cast<int>(root["feature_count"])) +
                             " features, this version computes " + std::to_string(kCandidateFeatureCount) +
                             ": train it again with rle_vision_train");
  }
  if (static_cast<int>(root["feature_version"]) != kCandidateFeatureVersion) {
    throw std::runtime_error(path + ": made for the features of another version (" +
                             (root["feature_version"].empty() ? std::string("1, absolute chroma")
                                                              : std::to_string(static_cast<int>(root["feature_version"]))) +
                             "; this one computes version " + std::to_string(kCandidateFeatureVersion) +
                             "): train it again with rle_vision_train");
  }
  BlobVerifier verifier;
  const cv::FileNode range = root["candidate_range"];
  std::vector<int> lo, hi;
  if (!range.empty()) range["min"] >> lo, range["max"] >> hi;
  if (range.empty() || lo.size() != 3 || hi.size() != 3 || !parseColorSpace(static_cast<std::string>(range["space"]), &verifier.candidate_range_.space)) {
    throw std::runtime_error(path + ": the verifier file holds no usable candidate_range (name, space, min, max)");
  }
  verifier.candidate_range_.name = static_cast<std::string>(range["name"]);
  verifier.candidate_range_.min_area_px = static_cast<uint32_t>(std::max(1, static_cast<int>(range["min_area_px"])));
  for (int c = 0; c < 3; ++c) {
    if (lo[c] < 0 || lo[c] > 255 || hi[c] < 0 || hi[c] > 255) throw std::runtime_error(path + ": candidate_range out of 0..255");
    verifier.candidate_range_.min[c] = static_cast<uint8_t>(lo[c]);
    verifier.candidate_range_.max[c] = static_cast<uint8_t>(hi[c]);
  }
  const cv::FileNode guard_scale = root["floor_guard_scale"];
  if (!guard_scale.empty()) {
    const double scale = guard_scale.isReal() || guard_scale.isInt() ? static_cast<double>(guard_scale) : 0.0;
    if (!(scale >= 1.0 && scale <= 16.0)) throw std::runtime_error(path + ": floor_guard_scale is not a number from 1 to 16");
    verifier.floor_guard_scale_ = scale;
  }
  // "model": one model, as files before the models across groups held it.
  std::vector<cv::FileNode> nodes;
  if (root["models"].empty()) nodes.push_back(root["model"]);
  for (const cv::FileNode& node : root["models"]) nodes.push_back(node);
  for (const cv::FileNode& node : nodes) {
    if (!everyVariableOrdered(node)) {
      throw std::runtime_error(path + ": a model in the verifier file uses categorical variables or a subset of the "
                               "features, which rle_vision_train never makes");
    }
    cv::Ptr<cv::ml::Boost> model = cv::ml::Boost::create();
    model->read(node);
    verifier.addModel(model);
  }
  if (!verifier.trained()) throw std::runtime_error(path + ": the verifier file holds no trained model");
  return verifier;
}

}  // namespace rle_vision
