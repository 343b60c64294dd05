// The verifier's own tree evaluation gives OpenCV's Boost::predict(PREDICT_SUM) bit for bit:
// on a model trained here (probes on its thresholds too, where <= decides) and on every model
// of the shipped ball verifier; files it could not read that way are refused.
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/ml.hpp>

#include "rle_vision/verify/blob_verifier.h"
#include "rle_vision/verify/boosted_trees.h"
#include "rle_vision/verify/candidate_features.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

// `count` feature rows: uniform noise, and every threshold of `model` put in its variable in
// turn (the value a split compares with <=).
cv::Mat probes(const cv::ml::Boost& model, int count, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat rows(count, kCandidateFeatureCount, CV_32F);
  rng.fill(rows, cv::RNG::UNIFORM, -1.0, 2.0);
  for (const cv::ml::DTrees::Split& split : model.getSplits()) {
    cv::Mat on_threshold = rows.row(static_cast<int>(rng.uniform(0, count))).clone();
    on_threshold.at<float>(split.varIdx) = split.c;
    rows.push_back(on_threshold);
  }
  return rows;
}

void expectOpenCvSums(const cv::ml::Boost& model, const cv::Mat& rows) {
  const BoostedTrees flat(model);
  ASSERT_TRUE(flat.usable());
  for (int i = 0; i < rows.rows; ++i) {
    const float expected = model.predict(rows.row(i), cv::noArray(), cv::ml::DTrees::PREDICT_SUM);
    ASSERT_EQ(flat.sum(rows.ptr<float>(i)), expected) << "row " << i;
  }
}

TEST(BoostedTrees, SumsAsOpenCvOnATrainedModel) {
  // Two classes apart in a few features, overlapping in the rest.
  cv::RNG rng(3);
  cv::Mat features(400, kCandidateFeatureCount, CV_32F);
  rng.fill(features, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::Mat labels(400, 1, CV_32S);
  for (int i = 0; i < features.rows; ++i) {
    labels.at<int>(i) = i % 2;
    features.at<float>(i, 3) += 0.4f * static_cast<float>(i % 2);
    features.at<float>(i, 17) -= 0.3f * static_cast<float>(i % 2);
  }
  // Depth 1 and 2: the complete depth-two trees (a depth-one tree's leaves repeated below);
  // depth 3: the walk.
  for (const int depth : {1, 2, 3}) {
    cv::Ptr<cv::ml::Boost> model = cv::ml::Boost::create();
    model->setBoostType(cv::ml::Boost::REAL);
    model->setWeakCount(60);
    model->setMaxDepth(depth);
    model->setUseSurrogates(false);
    model->train(cv::ml::TrainData::create(features, cv::ml::ROW_SAMPLE, labels));
    SCOPED_TRACE("depth " + std::to_string(depth));
    expectOpenCvSums(*model, probes(*model, 500, 11));
    expectOpenCvSums(*model, features);
  }
}

TEST(BoostedTrees, SumsAsOpenCvOnTheShippedVerifiersModels) {
  cv::FileStorage file(test::sourcePath("config/ball_verifier.yml.gz"), cv::FileStorage::READ);
  ASSERT_TRUE(file.isOpened());
  int models = 0;
  for (const cv::FileNode& node : file["rle_vision_verifier"]["models"]) {
    cv::Ptr<cv::ml::Boost> model = cv::ml::Boost::create();
    model->read(node);
    ASSERT_TRUE(model->isTrained());
    expectOpenCvSums(*model, probes(*model, 300, 5 + models));
    ++models;
  }
  EXPECT_GE(models, 2);
}

// The flat walk reads a feature by its split's variable, each split as ordered: a file whose
// models say otherwise is refused at load, with the reason.
TEST(BoostedTrees, AVerifierFileWithCategoricalVariablesOrASubsetIsRefused) {
  cv::RNG rng(8);
  cv::Mat features(200, kCandidateFeatureCount, CV_32F);
  rng.fill(features, cv::RNG::UNIFORM, 0.0, 1.0);
  std::vector<int> labels(200);
  for (int i = 0; i < 200; ++i) labels[static_cast<size_t>(i)] = features.at<float>(i, 0) > 0.5f;
  BlobVerifier verifier = BlobVerifier::train(features, labels);
  verifier.setCandidateRange(test::makeClass("ball", ColorSpace::YUV, {{0, 0, 0}}, {{255, 255, 255}}));
  const std::string path = testing::TempDir() + "/rle_vision_trees.yml";
  verifier.save(path);
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  const std::string good = text.str();
  EXPECT_NO_THROW(BlobVerifier::load(path));
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"var_type: [ 0,", "var_type: [ 1,"},
                                 {"var_idx: [ 0, 1,", "var_idx: [ 1, 0,"}}) {
    const size_t at = good.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    std::string bad = good;
    bad.replace(at, from.size(), to);
    std::ofstream(path) << bad;
    try {
      BlobVerifier::load(path);
      ADD_FAILURE() << "loaded a model with " << to;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("categorical variables or a subset"), std::string::npos) << e.what();
    }
  }
}

TEST(BoostedTrees, AnUntrainedModelIsNotUsable) {
  EXPECT_FALSE(BoostedTrees(*cv::ml::Boost::create()).usable());
}

}  // namespace
}  // namespace rle_vision
