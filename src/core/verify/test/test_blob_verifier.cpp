// The verifier with known answers: synthetic frames where a round, shaded ball and same-coloured
// non-balls (an upright bar, a shirt-like patch) share one colour range. Trained on some frames,
// it keeps the balls and drops the rest on frames it has not seen; the model file round-trips;
// bad input is refused with the reason.
#include <algorithm>
#include <cstdio>
#include <fstream>
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
  const std::string path = testing::TempDir() + "/rle_vision_verifier.yml";
  verifier.save(path);
  const BlobVerifier loaded = BlobVerifier::load(path);
  for (int i = 0; i < train.features().rows; ++i) {
    CandidateFeatures x;
    std::copy(train.features().ptr<float>(i), train.features().ptr<float>(i) + kCandidateFeatureCount, x.begin());
    EXPECT_FLOAT_EQ(loaded.score(x), verifier.score(x)) << "candidate " << i;
  }
  EXPECT_EQ(loaded.candidateRange().name, "ball");
  EXPECT_EQ(loaded.candidateRange().min, yellowRange().min);
  EXPECT_EQ(loaded.candidateRange().max, yellowRange().max);
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

}  // namespace
}  // namespace rle_vision
