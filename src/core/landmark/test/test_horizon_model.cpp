// The horizon model: the fit on data with a known answer, its file, and the shipped model on the
// simulator's scenes (a horizon outdoors, none indoors), as the nodes load it.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rle_vision/io/horizon_model_file.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

struct Samples {
  std::vector<HorizonFeatures> x;
  std::vector<int> y;
  std::vector<double> w;
  HorizonModel fit() const { return fitHorizonModel(x, y, w, 1.0); }
};

// Two classes apart along separation and sky_brighter only, the other features noise.
Samples syntheticSamples() {
  Samples s;
  std::vector<HorizonFeatures>* x = &s.x;
  std::vector<int>* y = &s.y;
  std::vector<double>* w = &s.w;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int i = 0; i < 400; ++i) {
    const int label = i % 2;
    HorizonFeatures f{};
    for (double& v : f) v = noise(rng);
    f[kSeparation] += label ? 2.0 : -2.0;
    f[kSkyBrighter] += label ? 1.0 : -1.0;
    f[kFromRegions] = 1;  // constant: standardised with scale 1
    x->push_back(f);
    y->push_back(label);
    w->push_back(1.0);
  }
  return s;
}

// Clear evidence either way (two to four standard deviations along the separating features)
// gets a probability near 1 or near 0.
void expectConfidentWhereTheEvidenceIsClear(const HorizonModel& m) {
  HorizonFeatures clear{};
  clear[kSeparation] = 4;
  clear[kSkyBrighter] = 2;
  EXPECT_GT(m.probability(clear), 0.99);
  clear[kSeparation] = -4;
  clear[kSkyBrighter] = -2;
  EXPECT_LT(m.probability(clear), 0.01);
}

TEST(HorizonModel, FitsTheFeaturesThatSeparateTheClasses) {
  const Samples samples = syntheticSamples();
  const std::vector<HorizonFeatures>& x = samples.x;
  const std::vector<int>& y = samples.y;
  const HorizonModel m = samples.fit();
  ASSERT_TRUE(m.valid);
  EXPECT_GT(m.weights[kSeparation], 2 * std::fabs(m.weights[kCoverage]));
  EXPECT_GT(m.weights[kSkyBrighter], 0);
  EXPECT_DOUBLE_EQ(m.scale[kFromRegions], 1.0);
  int right = 0;
  for (size_t i = 0; i < x.size(); ++i) right += (m.probability(x[i]) >= 0.5) == (y[i] == 1);
  EXPECT_GT(right, 0.95 * x.size());
  expectConfidentWhereTheEvidenceIsClear(m);
  // Deterministic: the same data give the same model.
  const HorizonModel again = samples.fit();
  EXPECT_EQ(again.weights, m.weights);
  EXPECT_EQ(again.bias, m.bias);
}

// The penalty picks the direction; the scale is refitted, so a strong penalty still gives
// probabilities near 0 and 1 where the evidence is clear (unscaled, they would all sit near 0.5).
TEST(HorizonModel, AStrongPenaltyKeepsTheProbabilityCalibrated) {
  const Samples samples = syntheticSamples();
  const HorizonModel weak = samples.fit();
  const HorizonModel strong = fitHorizonModel(samples.x, samples.y, samples.w, 1e5);
  ASSERT_TRUE(strong.valid);
  expectConfidentWhereTheEvidenceIsClear(strong);
  int agree = 0;
  for (const HorizonFeatures& f : samples.x) agree += (weak.probability(f) >= 0.5) == (strong.probability(f) >= 0.5);
  EXPECT_GT(agree, 0.95 * samples.x.size());
}

// Classes that one feature separates completely: the refitted scale stays finite (Platt's
// targets), so the probability is a confidence, not a step from 0 to 1. At the optimum the mean
// probability of each class is its target, (200 + 1) / (200 + 2) and 1 / (200 + 2): without the
// targets the scale would grow without bound and the means reach 1 and 0.
TEST(HorizonModel, SeparableClassesGetAFiniteScale) {
  Samples samples = syntheticSamples();
  for (size_t i = 0; i < samples.x.size(); ++i) samples.x[i][kSeparation] = samples.y[i] ? 3.0 : -3.0;
  const HorizonModel m = samples.fit();
  ASSERT_TRUE(m.valid);
  for (double weight : m.weights) EXPECT_LT(std::fabs(weight), 20.0);
  double positive_mean = 0, negative_mean = 0;
  for (size_t i = 0; i < samples.x.size(); ++i) {
    const double p = m.probability(samples.x[i]);
    (samples.y[i] == 1 ? positive_mean : negative_mean) += p / 200;
    if (samples.y[i] == 1) EXPECT_GT(p, 0.9);
    if (samples.y[i] == 0) EXPECT_LT(p, 0.1);
  }
  EXPECT_NEAR(positive_mean, 201.0 / 202, 2e-3);
  EXPECT_NEAR(negative_mean, 1.0 / 202, 2e-3);
}

TEST(HorizonModel, OneClassOnlyOrNoSamplesGiveNoModel) {
  std::vector<HorizonFeatures> x(10);
  std::vector<int> y(10, 1);
  std::vector<double> w(10, 1.0);
  EXPECT_FALSE(fitHorizonModel(x, y, w, 1.0).valid);
  EXPECT_FALSE(fitHorizonModel({}, {}, {}, 1.0).valid);
  y[3] = 0;
  w.pop_back();  // weights that do not match the samples
  EXPECT_FALSE(fitHorizonModel(x, y, w, 1.0).valid);
}

TEST(HorizonModelFile, WritesAndReadsBackTheSameModel) {
  const Samples samples = syntheticSamples();
  const HorizonModel m = samples.fit();
  const std::string yaml = horizonModelYaml(m, "made by a test\non two lines");
  EXPECT_EQ(yaml.rfind("# made by a test\n# on two lines\n", 0), 0u) << yaml;
  const HorizonModel back = parseHorizonModel(yaml, "test.yaml");
  ASSERT_TRUE(back.valid);
  for (int f = 0; f < kHorizonFeatureCount; ++f) {
    EXPECT_NEAR(back.weights[f], m.weights[f], 1e-8 * (1 + std::fabs(m.weights[f])));
    EXPECT_NEAR(back.mean[f], m.mean[f], 1e-8 * (1 + std::fabs(m.mean[f])));
  }
  EXPECT_NEAR(back.probability(samples.x[0]), m.probability(samples.x[0]), 1e-7);
  // Without a stop probability every candidate is weighed (files made before it too).
  EXPECT_GT(back.stop_probability, 1);
  EXPECT_EQ(yaml.find("stop_probability"), std::string::npos);
  HorizonModel stopping = m;
  stopping.stop_probability = 0.99;
  EXPECT_EQ(parseHorizonModel(horizonModelYaml(stopping, "test"), "test.yaml").stop_probability, 0.99);
}

TEST(HorizonModelFile, BrokenFilesAreRefusedWithTheLineAndTheReason) {
  const std::string good = horizonModelYaml(syntheticSamples().fit(), "test");
  auto refused = [](const std::string& text, const std::string& reason) {
    try {
      parseHorizonModel(text, "model.yaml");
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("model.yaml:", 0), 0u) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted: " << text;
  };
  std::string renamed = good;
  renamed.replace(renamed.find("separation"), 10, "separatoin");
  refused(renamed, "feature 1 must be 'separation'");
  std::string short_list = good;
  short_list.replace(short_list.find("bias:"), 5, "biass:");
  refused(short_list, "unknown key 'biass'");
  std::string word = good;
  const size_t weights = word.find("weights: [") + 10;
  word.replace(weights, word.find(',', weights) - weights, "heavy");
  refused(word, "'weights' holds something that is not a number");
  refused("features: [a]\n", "'features' must list the");
  refused(good + "stop_probability: 0.4\n", "'stop_probability' must be 0.5 or more");
  refused(good + "stop_probability: .nan\n", "'stop_probability'");
  EXPECT_THROW(loadHorizonModel("/nonexistent/model.yaml"), ConfigError);
  EXPECT_FALSE(horizonModelFromSetting("none").valid);
}

// The shipped model as the nodes load it: the horizon of the default scene's walking gait, and
// none indoors (a carpet with field lines, no sky in view).
TEST(HorizonModel, TheShippedModelFindsTheSimulatorsHorizonAndNoneIndoors) {
  LandmarkOptions options;
  options.horizon.model = horizonModelFromSetting("");
  ASSERT_TRUE(options.horizon.model.valid) << "config/horizon_model.yaml not found";
  LandmarkDetector detector;
  LandmarkResult result;
  const SceneSimulator outdoor(loadSceneConfig(test::sourcePath("config/scene_default.yaml")));
  const SceneSimulator indoor(loadSceneConfig(test::sourcePath("config/scene_indoor.yaml")));
  int found = 0, found_indoors = 0;
  double worst_deg = 0;
  for (int i = 0; i < 20; ++i) {
    const SimFrame frame = outdoor.render(13 * i, 13 * i / 30.0);
    detector.detectInImage(frame.image, options, &result);
    found += result.horizon.found;
    if (result.horizon.found) {
      worst_deg = std::max(worst_deg, lineAngleDifference(result.horizon.line.theta, frame.horizon.theta) * 180 / M_PI);
    }
    detector.detectInImage(indoor.render(13 * i, 13 * i / 30.0).image, options, &result);
    found_indoors += result.horizon.found;
  }
  EXPECT_EQ(found, 20);
  EXPECT_LT(worst_deg, 1.0);
  EXPECT_EQ(found_indoors, 0);
}

// With a model every candidate is weighed; the candidates carry the features the model reads.
TEST(HorizonModel, CandidatesCarryTheirEvidence) {
  const SceneSimulator outdoor(loadSceneConfig(test::sourcePath("config/scene_default.yaml")));
  const SimFrame frame = outdoor.render(0, 0.0);
  LandmarkOptions options;
  LandmarkDetector detector;
  LandmarkResult result;
  detector.detectInImage(frame.image, options, &result);
  HorizonDetector horizon;
  const std::vector<HorizonEstimate> candidates =
      horizon.candidates(frame.image, detector.edges(), options.edge_gain, result.lines, options.horizon);
  ASSERT_GE(candidates.size(), 2u);
  EXPECT_EQ(candidates.front().features[kFromRegions], 1);
  for (const HorizonEstimate& c : candidates) {
    for (int f = 0; f < kHorizonFeatureCount; ++f) EXPECT_TRUE(std::isfinite(c.features[f])) << horizonFeatureName(f);
    EXPECT_LE(c.features[kSeparation], 0);  // log-probabilities
    EXPECT_GE(c.features[kSeparation], std::log(0.01) - 1e-12);
  }
  // One of them is the true horizon, a colour step across the line.
  const auto truth = std::find_if(candidates.begin(), candidates.end(), [&](const HorizonEstimate& c) {
    double x = 0, y = 0;
    pointOnLine(c.line, &x, &y);
    return lineAngleDifference(c.line.theta, frame.horizon.theta) * 180 / M_PI < 1.0 &&
           std::fabs(signedDistance(frame.horizon, x, y)) < 3.0;
  });
  ASSERT_NE(truth, candidates.end());
  // The shipped model weighs it above every other candidate.
  const HorizonModel model = horizonModelFromSetting("");
  for (const HorizonEstimate& c : candidates) {
    if (lineAngleDifference(c.line.theta, truth->line.theta) > 1e-9 || std::fabs(c.line.intercept - truth->line.intercept) > 1e-9) {
      EXPECT_LE(model.probability(c.features), model.probability(truth->features));
    }
  }
}

// With a stop probability the detector takes the first candidate the model is that sure of
// and refines no further; above 1 it takes the most probable of all (the same frames, the same
// candidates in the same order as candidates() lists them).
TEST(HorizonModel, TheFirstCandidateTheModelIsSureOfEndsTheSearch) {
  const SceneSimulator outdoor(loadSceneConfig(test::sourcePath("config/scene_default.yaml")));
  LandmarkOptions options;
  options.horizon.model = horizonModelFromSetting("");
  ASSERT_TRUE(options.horizon.model.valid);
  LandmarkDetector detector;
  LandmarkResult result;
  HorizonDetector horizon;
  int stopped_early = 0;
  for (int i = 0; i < 10; ++i) {
    const SimFrame frame = outdoor.render(29 * i, 29 * i / 30.0);
    options.horizon.model.stop_probability = 2;
    detector.detectInImage(frame.image, options, &result);
    const std::vector<HorizonEstimate> all =
        horizon.candidates(frame.image, detector.edges(), options.edge_gain, result.lines, options.horizon);
    ASSERT_GE(all.size(), 2u);
    const auto most_probable = std::max_element(all.begin(), all.end(), [](const HorizonEstimate& a, const HorizonEstimate& b) {
      return a.confidence < b.confidence;
    });
    EXPECT_EQ(result.horizon.confidence, most_probable->confidence);
    EXPECT_EQ(result.horizon.line.theta, most_probable->line.theta);
    // A stop just below the second candidate's probability: the first that reaches it.
    const double stop = std::min(0.999999, all[1].confidence);
    const auto first_sure = std::find_if(all.begin(), all.end(), [&](const HorizonEstimate& c) { return c.confidence >= stop; });
    ASSERT_NE(first_sure, all.end());
    options.horizon.model.stop_probability = stop;
    detector.detectInImage(frame.image, options, &result);
    EXPECT_EQ(result.horizon.confidence, first_sure->confidence) << "frame " << i;
    EXPECT_EQ(result.horizon.line.theta, first_sure->line.theta) << "frame " << i;
    stopped_early += first_sure->confidence < most_probable->confidence;
  }
  // The rule changed the choice on some frames: the test tells the two apart.
  EXPECT_GT(stopped_early, 0);
}

}  // namespace
}  // namespace rle_vision
