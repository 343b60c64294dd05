// The verifier with known answers: synthetic frames where a round, shaded ball and same-coloured
// non-balls (an upright bar, a shirt-like patch) share one colour range. Trained on some frames,
// it keeps the balls and drops the rest on frames it has not seen; the model file round-trips;
// bad input is refused with the reason.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/verify/blob_verifier.h"
#include "rle_vision/verify/verifier_training.h"
#include "testing/test_helpers.h"
#include "testing/verifier_scenes.h"

namespace rle_vision {
namespace {

// A permissive yellow: the ball's shaded part, the bar and the patch all fall in it.
ColorClass yellowRange() { return test::makeClass("ball", ColorSpace::YUV, {{60, 0, 120}}, {{255, 110, 255}}); }

VerifierTrainingSet candidatesOf(int frames, uint64_t seed) {
  VerifierTrainingSet set(yellowRange());
  cv::RNG rng(seed);
  for (int i = 0; i < frames; ++i) {
    const test::VerifierFrame f = test::drawVerifierFrame(rng);
    set.addFrame(f.bgr, f.balls);
  }
  return set;
}

TEST(BlobVerifier, KeepsTheBallsAndDropsSameColouredShapesOnUnseenFrames) {
  const VerifierTrainingSet train = candidatesOf(60, 11), test = candidatesOf(40, 99);
  ASSERT_GE(train.positives(), 55);
  ASSERT_GE(static_cast<int>(train.labels().size()) - train.positives(), 110);  // the bars and the patches
  const BlobVerifier verifier = BlobVerifier::train(train.features(), train.labels());
  int kept_balls = 0, balls = 0, kept_others = 0, others = 0;
  for (int i = 0; i < test.features().rows; ++i) {
    CandidateFeatures x;
    std::copy(test.features().ptr<float>(i), test.features().ptr<float>(i) + kCandidateFeatureCount, x.begin());
    const bool kept = verifier.score(x) >= 0.5f;
    (test.labels()[i] ? balls : others) += 1;
    (test.labels()[i] ? kept_balls : kept_others) += kept;
  }
  std::printf("[ verifier ] unseen frames: %d/%d balls kept, %d/%d same-coloured shapes kept\n", kept_balls, balls,
              kept_others, others);
  ASSERT_GE(balls, 38);
  EXPECT_GE(kept_balls, balls * 95 / 100);
  EXPECT_LE(kept_others, others * 5 / 100);
}

TEST(BlobVerifier, ModelFileRoundTripsAndBadInputIsRefused) {
  const VerifierTrainingSet train = candidatesOf(20, 5);
  BlobVerifier verifier = BlobVerifier::train(train.features(), train.labels());
  verifier.setCandidateRange(yellowRange());
  verifier.setFloorGuardScale(2.5);
  const std::string path = testing::TempDir() + "/rle_vision_verifier.yml";
  verifier.save(path);
  const BlobVerifier loaded = BlobVerifier::load(path);
  EXPECT_DOUBLE_EQ(loaded.floorGuardScale(), 2.5);
  for (int i = 0; i < train.features().rows; ++i) {
    CandidateFeatures x;
    std::copy(train.features().ptr<float>(i), train.features().ptr<float>(i) + kCandidateFeatureCount, x.begin());
    EXPECT_FLOAT_EQ(loaded.score(x), verifier.score(x)) << "candidate " << i;
  }
  EXPECT_EQ(loaded.candidateRange().name, "ball");
  EXPECT_EQ(loaded.candidateRange().min, yellowRange().min);
  EXPECT_EQ(loaded.candidateRange().max, yellowRange().max);
  // A file made for the features of another version (none named: version 1, absolute chroma):
  // refused, with the fix.
  std::ifstream written(path);
  std::string text((std::istreambuf_iterator<char>(written)), std::istreambuf_iterator<char>());
  const size_t found = text.find("feature_version: " + std::to_string(kCandidateFeatureVersion) + "\n");
  ASSERT_NE(found, std::string::npos);
  const size_t at = text.rfind('\n', found) + 1;  // the line, with its indentation
  // A file from before the floor guard (no floor_guard_scale) loads with none (scale 1); a scale
  // that is not a number from 1 to 16 is refused.
  const std::string margin_line = "floor_guard_scale: 2.5000000000000000e+00\n";
  const size_t margin_at = text.find(margin_line);
  ASSERT_NE(margin_at, std::string::npos);
  const std::string margin_path = testing::TempDir() + "/rle_vision_verifier_margin.yml";
  const size_t margin_line_start = text.rfind('\n', margin_at) + 1;  // with its indentation
  std::ofstream(margin_path) << std::string(text).erase(margin_line_start, margin_at + margin_line.size() - margin_line_start);
  EXPECT_DOUBLE_EQ(BlobVerifier::load(margin_path).floorGuardScale(), 1.0);
  for (const char* bad : {"floor_guard_scale: 0.5\n", "floor_guard_scale: 17\n", "floor_guard_scale: .nan\n",
                          "floor_guard_scale: two\n"}) {
    std::ofstream(margin_path) << std::string(text).replace(margin_at, margin_line.size(), bad);
    EXPECT_THROW(BlobVerifier::load(margin_path), std::runtime_error) << bad;
  }
  const std::string old_path = testing::TempDir() + "/rle_vision_verifier_v1.yml";
  std::ofstream(old_path) << text.erase(at, text.find('\n', at) + 1 - at);
  try {
    BlobVerifier::load(old_path);
    ADD_FAILURE() << "a verifier file of version 1 loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("train it again with rle_vision_train"), std::string::npos) << e.what();
  }
  // One class only, wrong sizes, unreadable and foreign files: refused with the reason.
  EXPECT_THROW(BlobVerifier::train(train.features(), std::vector<int>(train.labels().size(), 0)), std::invalid_argument);
  EXPECT_THROW(BlobVerifier::train(train.features().colRange(0, 10).clone(), train.labels()), std::invalid_argument);
  EXPECT_THROW(BlobVerifier::load("/nonexistent/verifier.yml"), std::runtime_error);
  const std::string foreign = testing::TempDir() + "/rle_vision_not_a_verifier.yml";
  std::ofstream(foreign) << "%YAML:1.0\nsomething: 1\n";
  EXPECT_THROW(BlobVerifier::load(foreign), std::runtime_error);
  std::ofstream(foreign) << "this is not YAML: [";
  EXPECT_THROW(BlobVerifier::load(foreign), std::runtime_error);
  EXPECT_FALSE(BlobVerifier().trained());
  EXPECT_THROW(BlobVerifier().save(path), std::runtime_error);
}

// Features of one synthetic candidate: feature 0 and feature 5 set, the rest 0.
CandidateFeatures syntheticCandidate(float f0, float f5) {
  CandidateFeatures x{};
  x[0] = f0;
  x[5] = f5;
  return x;
}

// Three groups (halls). In groups 1 and 2 feature 0 tells objects (around +1) from the rest
// (around -1) and feature 5 is always 0. In group 0 feature 0 tells nothing, and every object
// has feature 5 at 3: a cue only that hall shows (a colour of its light).
void threeHalls(cv::Mat* features, std::vector<int>* labels, std::vector<int>* groups) {
  cv::RNG rng(7);
  for (int g = 0; g < 3; ++g) {
    for (int i = 0; i < 240; ++i) {
      const bool object = i % 6 == 0;
      const float f0 = g == 0 ? static_cast<float>(rng.gaussian(1.0)) : (object ? 1.0f : -1.0f) + static_cast<float>(rng.gaussian(0.3));
      const CandidateFeatures x = syntheticCandidate(f0, g == 0 && object ? 3.0f : 0.0f);
      features->push_back(cv::Mat(1, kCandidateFeatureCount, CV_32F, const_cast<float*>(x.data())));
      labels->push_back(object);
      groups->push_back(g);
    }
  }
}

TEST(BlobVerifier, AcrossGroupsACueOnlyOneHallTaughtDoesNotDecide) {
  cv::Mat features;
  std::vector<int> labels, groups;
  threeHalls(&features, &labels, &groups);
  const BlobVerifier one = BlobVerifier::train(features, labels);
  const BlobVerifier across = BlobVerifier::trainAcrossGroups(features, labels, groups);
  EXPECT_EQ(one.modelCount(), 1);
  ASSERT_EQ(across.modelCount(), 3);
  // Not an object by the cue every other hall agrees on, but with hall 0's cue: one model over
  // all halls takes it, the models trained without one hall each do not all agree.
  const CandidateFeatures lookalike = syntheticCandidate(-1.2f, 3.0f);
  EXPECT_GE(one.score(lookalike), 0.5f);
  EXPECT_LT(across.score(lookalike), 0.5f);
  // What every hall calls an object, and what none does, both models judge alike.
  EXPECT_GE(across.score(syntheticCandidate(1.2f, 0.0f)), 0.5f);
  EXPECT_LT(across.score(syntheticCandidate(-1.2f, 0.0f)), 0.5f);
  // A group whose others hold no object adds no model; one group alone: one model over all.
  std::vector<int> only_group0_objects(labels);
  for (size_t i = 0; i < labels.size(); ++i) only_group0_objects[i] = groups[i] == 0 && labels[i];
  EXPECT_EQ(BlobVerifier::trainAcrossGroups(features, only_group0_objects, groups).modelCount(), 2);
  EXPECT_EQ(BlobVerifier::trainAcrossGroups(features, labels, std::vector<int>(labels.size(), 4)).modelCount(), 1);
  EXPECT_THROW(BlobVerifier::trainAcrossGroups(features, labels, {0, 1}), std::invalid_argument);
}

TEST(BlobVerifier, ModelsAcrossGroupsRoundTripInACompressedFile) {
  cv::Mat features;
  std::vector<int> labels, groups;
  threeHalls(&features, &labels, &groups);
  BlobVerifier verifier = BlobVerifier::trainAcrossGroups(features, labels, groups);
  verifier.setCandidateRange(yellowRange());
  const std::string path = testing::TempDir() + "/rle_vision_verifier_groups.yml.gz";
  verifier.save(path, "made by a test");
  const BlobVerifier loaded = BlobVerifier::load(path);
  EXPECT_EQ(loaded.modelCount(), 3);
  for (int i = 0; i < features.rows; i += 7) {
    CandidateFeatures x;
    std::copy(features.ptr<float>(i), features.ptr<float>(i) + kCandidateFeatureCount, x.begin());
    EXPECT_FLOAT_EQ(loaded.score(x), verifier.score(x)) << "candidate " << i;
  }
}

// The candidates' range holds the ball as calibrated in every hall; it cannot mix colour spaces
// or cover a wrapping hue.
TEST(CandidateRange, CoversEveryHallsRange) {
  const ColorClass a = test::makeClass("ball", ColorSpace::YUV, {{100, 60, 130}}, {{180, 100, 160}});
  const ColorClass b = test::makeClass("ball", ColorSpace::YUV, {{150, 50, 140}}, {{250, 90, 170}});
  const ColorClass both = rangeCovering({a, b});
  EXPECT_EQ(both.min, (Channels{{100, 50, 130}}));
  EXPECT_EQ(both.max, (Channels{{250, 100, 170}}));
  EXPECT_EQ(rangeCovering({a}).max, a.max);
  EXPECT_THROW(rangeCovering({}), std::invalid_argument);
  EXPECT_THROW(rangeCovering({a, test::makeClass("ball", ColorSpace::HSV, {{10, 0, 0}}, {{20, 255, 255}})}),
               std::invalid_argument);
  EXPECT_THROW(rangeCovering({test::makeClass("red", ColorSpace::HSV, {{170, 0, 0}}, {{10, 255, 255}})}),
               std::invalid_argument);
}

// A permissive range that also takes the floor: without the floor's colour first the ball and
// the floor are one candidate, centred nowhere near the ball; with it the ball is its own.
TEST(CandidateRange, TheFloorsColourFirstKeepsTheBallACandidateOfItsOwn) {
  cv::Mat bgr(200, 240, CV_8UC3, cv::Scalar(60, 120, 70));
  cv::RNG rng(3);
  cv::Mat noise(bgr.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::NORMAL, 0, 3);
  bgr += noise;
  const cv::Point centre(170, 60);
  cv::circle(bgr, centre, 10, cv::Scalar(40, 200, 230), cv::FILLED);
  cv::Mat floor_yuv, ball_yuv;
  cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar(60, 120, 70)), floor_yuv, cv::COLOR_BGR2YUV);
  cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar(40, 200, 230)), ball_yuv, cv::COLOR_BGR2YUV);
  Channels floor_lo, floor_hi, lo, hi;
  for (int c = 0; c < 3; ++c) {
    const int f = floor_yuv.at<cv::Vec3b>(0)[c], b = ball_yuv.at<cv::Vec3b>(0)[c];
    floor_lo[c] = static_cast<uint8_t>(std::max(0, f - 15));
    floor_hi[c] = static_cast<uint8_t>(std::min(255, f + 15));
    lo[c] = static_cast<uint8_t>(std::max(0, std::min(f, b) - 20));
    hi[c] = static_cast<uint8_t>(std::min(255, std::max(f, b) + 20));
  }
  const ColorClass permissive = test::makeClass("ball", ColorSpace::YUV, lo, hi);
  const ColorClass floor = test::makeClass("field", ColorSpace::YUV, floor_lo, floor_hi);
  auto nearBall = [&](const std::vector<Region>& candidates) {
    return std::count_if(candidates.begin(), candidates.end(), [&](const Region& r) {
      return std::hypot(r.cx - centre.x, r.cy - centre.y) < 2 && r.right - r.left < 25;
    });
  };
  Segmenter segmenter;
  std::vector<Region> candidates;
  candidateRegions(&segmenter, bgr, permissive, nullptr, 20, &candidates);
  EXPECT_EQ(nearBall(candidates), 0);
  ASSERT_FALSE(candidates.empty());
  EXPECT_GT(candidates.front().area, 40000u);  // the floor and the ball, one region
  candidateRegions(&segmenter, bgr, permissive, &floor, 20, &candidates);
  EXPECT_EQ(nearBall(candidates), 1);
  for (const Region& r : candidates) EXPECT_EQ(r.label, 2);  // the floor's own regions are not candidates
}

// Grouped cross-validation counts every labelled object, found or not, and every kept candidate.
// On floors with a fringe, the floor guard's scale chosen on it takes the fringe (a ball at a
// strip's end is one candidate with it without a guard, centred off the ball) and leaves the
// balls (the floor grown 3 times takes them).
TEST(FloorGuardScale, IsChosenLargeEnoughToTakeTheFringeAndSmallEnoughToLeaveTheBalls) {
  const test::FringeScene scene = test::fringeScene();
  ASSERT_EQ(floorGuardScalesTried(), (std::vector<double>{1.0, 1.5, 2.0, 2.5, 3.0}));
  std::vector<VerifierTrainingSet> sets;
  for (double scale : floorGuardScalesTried()) sets.emplace_back(scene.permissive, 20, scale);
  cv::RNG rng(21);
  for (int group = 0; group < 3; ++group) {
    for (int i = 0; i < 12; ++i) {
      const test::VerifierFrame f = test::drawFringeFrame(rng);
      for (VerifierTrainingSet& set : sets) {
        set.setGroup(group);
        set.addFrame(f.bgr, f.balls, &scene.floor);
      }
    }
  }
  // Scale 1.5: every ball is a candidate of its own, and so is every bar.
  EXPECT_EQ(sets[1].objectsInGroup(0), 24);
  EXPECT_EQ(sets[1].positives(), 72);
  EXPECT_EQ(static_cast<int>(sets[1].labels().size()), 108);
  // No guard: the balls at a strip's end are not.
  EXPECT_LE(sets[0].positives(), 40);
  const std::vector<HeldOutCounts> held = crossValidateByGroup(sets[1]);
  ASSERT_EQ(held.size(), 3u);
  for (const HeldOutCounts& h : held) {
    EXPECT_EQ(h.objects, 24);
    EXPECT_GE(h.found, 23) << "group " << h.group;
    EXPECT_LE(h.kept, h.kept_on_object + 1) << "group " << h.group;
  }
  std::vector<double> f1;
  const double chosen = chooseFloorGuardScale(sets, &f1);
  std::printf("[ floor    ] held-out mean F1 by scale: %.3f %.3f %.3f %.3f %.3f, chosen %.1f\n", f1[0], f1[1], f1[2],
              f1[3], f1[4], chosen);
  EXPECT_GE(chosen, 1.5);
  EXPECT_LE(chosen, 2.5);
  const double best = *std::max_element(f1.begin(), f1.end());
  EXPECT_LT(f1[0], best - 0.1);  // the fringe taken with the balls
  EXPECT_LT(f1[4], best - 0.1);  // the balls taken with the floor
  // One group: nothing can be held out, the first set's scale.
  std::vector<VerifierTrainingSet> one;
  one.emplace_back(scene.permissive, 20, 1.5);
  one.back().addFrame(test::drawFringeFrame(rng).bgr, {}, &scene.floor);
  EXPECT_DOUBLE_EQ(chooseFloorGuardScale(one), 1.5);
  EXPECT_THROW(chooseFloorGuardScale({}), std::invalid_argument);
  EXPECT_THROW(VerifierTrainingSet(scene.permissive, 20, 0.5), std::invalid_argument);
  EXPECT_THROW(VerifierTrainingSet(scene.permissive, 20, std::nan("")), std::invalid_argument);
}

TEST(FloorGuardScale, ARangeGrowsAboutItsCentreAndStaysInTheChannel) {
  const ColorClass range = test::makeClass("field", ColorSpace::YUV, {{100, 10, 240}}, {{120, 30, 250}});
  const ColorClass same = scaledRange(range, 1.0);
  EXPECT_EQ(same.min, range.min);
  EXPECT_EQ(same.max, range.max);
  const ColorClass grown = scaledRange(range, 2.0);
  EXPECT_EQ(grown.min, (Channels{{90, 0, 235}}));
  EXPECT_EQ(grown.max, (Channels{{130, 40, 255}}));
  const ColorClass odd = scaledRange(range, 1.5);  // half widths 15 and 7.5: grown outwards
  EXPECT_EQ(odd.min, (Channels{{95, 5, 237}}));
  EXPECT_EQ(odd.max, (Channels{{125, 35, 253}}));
  EXPECT_THROW(scaledRange(range, 0.9), std::invalid_argument);
  ColorClass hue = range;
  hue.space = ColorSpace::HSV;
  hue.min[0] = 170, hue.max[0] = 10;
  EXPECT_THROW(scaledRange(hue, 2.0), std::invalid_argument);
}

}  // namespace
}  // namespace rle_vision
