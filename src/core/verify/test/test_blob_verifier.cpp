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

#include "rle_vision/color/color_table.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/verify/blob_verifier.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

const cv::Scalar kYellow(40, 200, 230);  // BGR

struct Frame {
  cv::Mat bgr;
  std::vector<cv::Rect> balls;
};

// A floor with a shaded ball (lit from above: its lower part darker, partly out of the range)
// and, in the same yellow, an upright bar and a ragged patch, at seeded places and sizes.
Frame drawFrame(cv::RNG& rng) {
  Frame f;
  f.bgr = cv::Mat(240, 320, CV_8UC3, cv::Scalar(60, 120, 70));
  cv::Mat noise(f.bgr.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::NORMAL, 0, 4);
  f.bgr += noise;
  const int radius = rng.uniform(6, 16);
  const cv::Point centre(rng.uniform(20, 140), rng.uniform(40, 220));
  for (int r = radius; r > 0; --r) {  // darker towards the bottom right: a lit crescent
    const double shade = 0.55 + 0.45 * r / radius;
    cv::circle(f.bgr, centre + cv::Point((radius - r) / 2, (radius - r) / 2), r, kYellow * shade, cv::FILLED, cv::LINE_AA);
  }
  cv::circle(f.bgr, centre - cv::Point(radius / 3, radius / 3), std::max(1, radius / 4), kYellow, cv::FILLED);
  f.balls.push_back(cv::Rect(centre.x - radius, centre.y - radius, 2 * radius + 1, 2 * radius + 1));
  const int bar_w = rng.uniform(5, 10);
  cv::rectangle(f.bgr, cv::Rect(rng.uniform(170, 220), rng.uniform(20, 120), bar_w, bar_w * rng.uniform(4, 8)), kYellow,
                cv::FILLED);
  std::vector<cv::Point> patch;
  const cv::Point at(rng.uniform(240, 290), rng.uniform(60, 200));
  for (int k = 0; k < 9; ++k) {
    const double a = k * 2 * M_PI / 9, r = rng.uniform(10, 28);
    patch.emplace_back(at + cv::Point(static_cast<int>(r * std::cos(a)), static_cast<int>(r * std::sin(a))));
  }
  cv::fillPoly(f.bgr, std::vector<std::vector<cv::Point>>{patch}, kYellow * 0.9);
  return f;
}

struct Candidates {
  cv::Mat features;          // one row per candidate
  std::vector<int> on_ball;  // its centroid inside a ball's box
};

void collect(const Frame& f, const ColorTable& table, Segmenter* segmenter, Candidates* out) {
  std::vector<Region> regions;
  segmenter->segment(f.bgr, PixelFormat::BGR8, table, &regions);
  for (const Region& r : regions) {
    if (r.area < 20) continue;
    CandidateFeatures x;
    candidateFeatures(f.bgr, r, &x);
    out->features.push_back(cv::Mat(1, kCandidateFeatureCount, CV_32F, x.data()).clone());
    bool on = false;
    for (const cv::Rect& b : f.balls) on = on || b.contains(cv::Point(static_cast<int>(r.cx), static_cast<int>(r.cy)));
    out->on_ball.push_back(on);
  }
}

ColorTable yellowTable() {
  // A permissive yellow: the ball's shaded part, the bar and the patch all fall in it.
  return ColorTable({test::makeClass("ball", ColorSpace::YUV, {{60, 0, 120}}, {{255, 110, 255}})});
}

TEST(BlobVerifier, KeepsTheBallsAndDropsSameColouredShapesOnUnseenFrames) {
  const ColorTable table = yellowTable();
  Segmenter segmenter;
  Candidates train, test;
  cv::RNG train_rng(11), test_rng(99);
  for (int i = 0; i < 60; ++i) collect(drawFrame(train_rng), table, &segmenter, &train);
  for (int i = 0; i < 40; ++i) collect(drawFrame(test_rng), table, &segmenter, &test);
  const int train_balls = static_cast<int>(std::count(train.on_ball.begin(), train.on_ball.end(), 1));
  ASSERT_GE(train_balls, 55);
  ASSERT_GE(static_cast<int>(train.on_ball.size()) - train_balls, 110);  // the bars and the patches
  const BlobVerifier verifier = BlobVerifier::train(train.features, train.on_ball);
  int kept_balls = 0, balls = 0, kept_others = 0, others = 0;
  for (int i = 0; i < test.features.rows; ++i) {
    CandidateFeatures x;
    std::copy(test.features.ptr<float>(i), test.features.ptr<float>(i) + kCandidateFeatureCount, x.begin());
    const bool kept = verifier.score(x) >= 0.5f;
    (test.on_ball[i] ? balls : others) += 1;
    (test.on_ball[i] ? kept_balls : kept_others) += kept;
  }
  std::printf("[ verifier ] unseen frames: %d/%d balls kept, %d/%d same-coloured shapes kept\n", kept_balls, balls,
              kept_others, others);
  ASSERT_GE(balls, 38);
  EXPECT_GE(kept_balls, balls * 95 / 100);
  EXPECT_LE(kept_others, others * 5 / 100);
}

TEST(BlobVerifier, ModelFileRoundTripsAndBadInputIsRefused) {
  const ColorTable table = yellowTable();
  Segmenter segmenter;
  Candidates train;
  cv::RNG rng(5);
  for (int i = 0; i < 20; ++i) collect(drawFrame(rng), table, &segmenter, &train);
  const BlobVerifier verifier = BlobVerifier::train(train.features, train.on_ball);
  const std::string path = testing::TempDir() + "/rle_vision_verifier.yml";
  verifier.save(path);
  const BlobVerifier loaded = BlobVerifier::load(path);
  for (int i = 0; i < train.features.rows; ++i) {
    CandidateFeatures x;
    std::copy(train.features.ptr<float>(i), train.features.ptr<float>(i) + kCandidateFeatureCount, x.begin());
    EXPECT_FLOAT_EQ(loaded.score(x), verifier.score(x)) << "candidate " << i;
  }
  // One class only, wrong sizes, unreadable and foreign files: refused with the reason.
  EXPECT_THROW(BlobVerifier::train(train.features, std::vector<int>(train.on_ball.size(), 0)), std::invalid_argument);
  EXPECT_THROW(BlobVerifier::train(train.features.colRange(0, 10).clone(), train.on_ball), std::invalid_argument);
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
