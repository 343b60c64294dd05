// The verifier's model against OpenCV ml's other learners, on the same candidates and features
// (rle_vision_eval_verifier --compare-models; issue 30 asks for the comparison): an SVM with an
// RBF kernel and a small MLP, both on standardised features with the two classes weighted
// equally; and the shipped model's boosted trees given one feature more, the candidate's height
// above the field boundary (the boundary as a feature rather than a gate). The package ships
// boosted trees on the 82 features (verify/blob_verifier.h); these are only measured.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>

#include "rle_vision/verify/candidate_features.h"

namespace rle_vision {
namespace bench {

class AlternativeModel {
 public:
  enum class Kind { kSvm, kMlp, kBoostWithField };

  // The SVM trains on every positive and at most `max_negatives` negatives (a fixed-seed draw):
  // an RBF SVM's training grows with the square of the samples.
  AlternativeModel(Kind kind, const cv::Mat& features, const std::vector<int>& labels, int max_negatives = 6000)
      : kind_(kind) {
    cv::reduce(features, mean_, 0, cv::REDUCE_AVG);
    cv::Mat centred = features - cv::repeat(mean_, features.rows, 1);
    cv::reduce(centred.mul(centred), sd_, 0, cv::REDUCE_AVG);
    cv::sqrt(sd_, sd_);
    sd_ = cv::max(sd_, 1e-6);
    const cv::Mat x = standardised(features);
    const int positives = static_cast<int>(std::count(labels.begin(), labels.end(), 1));
    const int negatives = static_cast<int>(labels.size()) - positives;
    if (kind_ == Kind::kSvm) trainSvm(x, labels, positives, negatives, max_negatives);
    else if (kind_ == Kind::kMlp) trainMlp(x, labels, positives, negatives);
    else trainBoost(features, labels, positives, negatives);
  }

  // `features`: one row (CV_32F), as many columns as the model was trained on.
  bool keep(const cv::Mat& features) const {
    if (kind_ == Kind::kBoostWithField) return boost_->predict(features, cv::noArray(), cv::ml::DTrees::PREDICT_SUM) >= 0;
    const cv::Mat x = standardised(features);
    if (kind_ == Kind::kSvm) return svm_->predict(x) > 0.5f;
    cv::Mat out;
    mlp_->predict(x, out);
    return out.at<float>(0, 0) > 0.0f;
  }

  static const char* name(Kind kind) {
    return kind == Kind::kSvm   ? "SVM (RBF, C 1, gamma 1/82)"
           : kind == Kind::kMlp ? "MLP (82-16-1, RPROP)"
                                : "verifier + height above the field as feature";
  }

 private:
  cv::Mat standardised(const cv::Mat& features) const {
    return (features - cv::repeat(mean_, features.rows, 1)) / cv::repeat(sd_, features.rows, 1);
  }

  void trainSvm(const cv::Mat& x, const std::vector<int>& labels, int positives, int negatives, int max_negatives) {
    cv::RNG rng(7);
    const double keep_negative = std::min(1.0, static_cast<double>(max_negatives) / std::max(1, negatives));
    cv::Mat samples, responses;
    int kept_negatives = 0;
    for (int i = 0; i < x.rows; ++i) {
      if (!labels[i] && rng.uniform(0.0, 1.0) >= keep_negative) continue;
      samples.push_back(x.row(i));
      responses.push_back(labels[i]);
      kept_negatives += !labels[i];
    }
    svm_ = cv::ml::SVM::create();
    svm_->setType(cv::ml::SVM::C_SVC);
    svm_->setKernel(cv::ml::SVM::RBF);
    svm_->setC(1.0);
    svm_->setGamma(1.0 / kCandidateFeatureCount);
    cv::Mat weights = (cv::Mat_<double>(2, 1) << 1.0, static_cast<double>(kept_negatives) / std::max(1, positives));
    svm_->setClassWeights(weights);
    svm_->train(samples, cv::ml::ROW_SAMPLE, responses);
  }

  void trainMlp(const cv::Mat& x, const std::vector<int>& labels, int positives, int negatives) {
    cv::Mat responses(x.rows, 1, CV_32F), weights(x.rows, 1, CV_32F);
    for (int i = 0; i < x.rows; ++i) {
      responses.at<float>(i) = labels[i] ? 1.0f : -1.0f;
      weights.at<float>(i) = labels[i] ? 0.5f / std::max(1, positives) : 0.5f / std::max(1, negatives);
    }
    weights *= static_cast<float>(x.rows);
    mlp_ = cv::ml::ANN_MLP::create();
    mlp_->setLayerSizes(std::vector<int>{kCandidateFeatureCount, 16, 1});
    mlp_->setActivationFunction(cv::ml::ANN_MLP::SIGMOID_SYM, 1, 1);
    mlp_->setTrainMethod(cv::ml::ANN_MLP::RPROP);
    mlp_->setTermCriteria(cv::TermCriteria(cv::TermCriteria::MAX_ITER | cv::TermCriteria::EPS, 300, 1e-4));
    cv::theRNG().state = 7;  // the weights' initialisation: deterministic
    mlp_->train(cv::ml::TrainData::create(x, cv::ml::ROW_SAMPLE, responses, cv::noArray(), cv::noArray(), weights));
  }

  // As BlobVerifier::train: Real AdaBoost, 100 depth-2 trees, the classes weighted equally.
  void trainBoost(const cv::Mat& features, const std::vector<int>& labels, int positives, int negatives) {
    cv::Mat responses(features.rows, 1, CV_32S), weights(features.rows, 1, CV_32F);
    for (int i = 0; i < features.rows; ++i) {
      responses.at<int>(i) = labels[i];
      weights.at<float>(i) = 0.5f / (labels[i] ? positives : negatives) * features.rows;
    }
    boost_ = cv::ml::Boost::create();
    boost_->setBoostType(cv::ml::Boost::REAL);
    boost_->setWeakCount(100);
    boost_->setMaxDepth(2);
    boost_->setWeightTrimRate(0);
    boost_->setUseSurrogates(false);
    boost_->train(cv::ml::TrainData::create(features, cv::ml::ROW_SAMPLE, responses, cv::noArray(), cv::noArray(), weights));
  }

  Kind kind_;
  cv::Mat mean_, sd_;
  cv::Ptr<cv::ml::SVM> svm_;
  cv::Ptr<cv::ml::ANN_MLP> mlp_;
  cv::Ptr<cv::ml::Boost> boost_;
};

}  // namespace bench
}  // namespace rle_vision
