// The verifier at run time, with known answers: on synthetic frames where a ball, a bar and a
// patch share one colour, the tracker's blobs of that class are screened (the ball kept with its
// score, the others dropped) while another class's blobs pass unscored; the cap scores the
// largest candidates only; a colours file names the verifier and may take its range from it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/io/color_config.h"
#include "rle_vision/tracking/color_tracker.h"
#include "rle_vision/verify/candidate_screen.h"
#include "rle_vision/verify/verifier_training.h"
#include "testing/test_helpers.h"
#include "testing/verifier_scenes.h"

namespace rle_vision {
namespace {

ColorClass yellowRange() { return test::makeClass("ball", ColorSpace::YUV, {{60, 0, 120}}, {{255, 110, 255}}, 20); }
// Pure blue squares, far from the yellow range, in a class without a verifier.
ColorClass blueRange() { return test::makeClass("goal", ColorSpace::YUV, {{0, 170, 0}}, {{255, 255, 110}}, 20); }

std::shared_ptr<const BlobVerifier> trainedVerifier() {
  static std::shared_ptr<const BlobVerifier> verifier = [] {
    VerifierTrainingSet set(yellowRange());
    cv::RNG rng(11);
    for (int i = 0; i < 60; ++i) {
      const test::VerifierFrame f = test::drawVerifierFrame(rng);
      set.addFrame(f.bgr, f.balls);
    }
    BlobVerifier v = BlobVerifier::train(set.features(), set.labels());
    v.setCandidateRange(yellowRange());
    return std::make_shared<const BlobVerifier>(std::move(v));
  }();
  return verifier;
}

bool inside(const TrackedBlob& b, const cv::Rect& box) {
  return b.region.cx >= box.x && b.region.cx < box.br().x && b.region.cy >= box.y && b.region.cy < box.br().y;
}

TEST(CandidateScreen, KeepsTheBallsWithTheirScoresDropsSameColouredShapesAndPassesOtherClasses) {
  const ColorTable table({blueRange(), yellowRange()});  // the ball is label 2: found by name
  CandidateScreen screen({{"ball", trainedVerifier(), 0.5}});
  cv::RNG rng(99);
  int balls = 0, balls_kept = 0, others_before = 0, others_kept = 0, goals = 0;
  for (int i = 0; i < 30; ++i) {
    test::VerifierFrame f = test::drawVerifierFrame(rng);
    const cv::Rect goal(rng.uniform(0, 290), rng.uniform(0, 210), 24, 24);
    cv::rectangle(f.bgr, goal, cv::Scalar(200, 40, 30), cv::FILLED);
    ColorTracker tracker;
    std::vector<TrackedBlob> blobs;
    tracker.process(f.bgr, PixelFormat::BGR8, table, 0.0, &blobs);
    std::vector<double> aligned;
    for (const TrackedBlob& b : blobs) aligned.push_back(b.region.cx);
    ASSERT_TRUE(screen.hasCandidates(table, blobs));
    for (const TrackedBlob& b : blobs) others_before += b.region.label == 2 && !inside(b, f.balls[0]);
    const ScreeningCounts counts = screen.apply(f.bgr, table, &blobs, &aligned);
    EXPECT_EQ(counts.scored, counts.candidates);
    EXPECT_EQ(counts.over_cap, 0u);
    ASSERT_EQ(aligned.size(), blobs.size());
    bool ball_kept = false;
    for (size_t k = 0; k < blobs.size(); ++k) {
      const TrackedBlob& b = blobs[k];
      EXPECT_EQ(aligned[k], b.region.cx) << "the aligned values follow their blobs";
      if (b.region.label == 1) {
        EXPECT_TRUE(std::isnan(b.score)) << "a class without a verifier is not scored";
        goals += inside(b, goal);
        continue;
      }
      EXPECT_GE(b.score, 0.5f);
      EXPECT_LE(b.score, 1.0f);
      if (inside(b, f.balls[0])) ball_kept = true;
      else ++others_kept;
    }
    ++balls;
    balls_kept += ball_kept;
  }
  std::printf("[ screen ] %d/%d balls kept, %d/%d same-coloured shapes kept, %d goals passed\n", balls_kept, balls,
              others_kept, others_before, goals);
  EXPECT_GE(balls_kept, 28);
  EXPECT_GE(others_before, 55);
  EXPECT_LE(others_kept, 3);
  EXPECT_EQ(goals, 30);
}

// A colour set swapped in at run time (learned ranges) may order the classes otherwise: the
// verifier follows its class by name, with one screen across both tables.
TEST(CandidateScreen, FollowsItsClassByNameWhenTheTableChanges) {
  CandidateScreen screen({{"ball", trainedVerifier(), 0.5}});
  cv::RNG rng(5);
  const test::VerifierFrame f = test::drawVerifierFrame(rng);
  for (const ColorTable& table : {ColorTable({blueRange(), yellowRange()}), ColorTable({yellowRange(), blueRange()}),
                                  ColorTable({blueRange()})}) {
    ColorTracker tracker;
    std::vector<TrackedBlob> blobs;
    tracker.process(f.bgr, PixelFormat::BGR8, table, 0.0, &blobs);
    const int ball_label = table.indexOf("ball") + 1;
    const ScreeningCounts counts = screen.apply(f.bgr, table, &blobs);
    int ball_blobs = 0;
    for (const TrackedBlob& b : blobs) {
      ball_blobs += b.region.label == ball_label;
      EXPECT_EQ(std::isnan(b.score), b.region.label != ball_label) << "only the ball class is scored";
    }
    EXPECT_EQ(counts.candidates > 0, ball_label > 0);
    EXPECT_LE(ball_blobs, 1) << "the bar and the patch are dropped, in either order of the classes";
  }
}

TEST(CandidateScreen, ScoresTheLargestCandidatesUpToTheCapAndDropsTheRestUnjudged) {
  const ColorTable table({yellowRange()});
  cv::Mat frame(120, 200, CV_8UC3, cv::Scalar(60, 120, 70));
  const int sizes[3] = {8, 14, 11};  // squares, their order in the frame not their size order
  for (int i = 0; i < 3; ++i) cv::rectangle(frame, cv::Rect(20 + 60 * i, 40, sizes[i], sizes[i]), cv::Scalar(40, 200, 230), cv::FILLED);
  ColorTracker tracker;
  std::vector<TrackedBlob> blobs;
  tracker.process(frame, PixelFormat::BGR8, table, 0.0, &blobs);
  ASSERT_EQ(blobs.size(), 3u);
  CandidateScreen screen({{"ball", trainedVerifier(), 0.0}}, 2);  // min_score 0: whatever is scored is kept
  const ScreeningCounts counts = screen.apply(frame, table, &blobs);
  EXPECT_EQ(counts.candidates, 3u);
  EXPECT_EQ(counts.scored, 2u);
  EXPECT_EQ(counts.over_cap, 1u);
  EXPECT_EQ(counts.rejected, 0u);
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_EQ(blobs[0].region.area, 14u * 14u);  // frame order kept among those scored
  EXPECT_EQ(blobs[1].region.area, 11u * 11u);
  for (const TrackedBlob& b : blobs) EXPECT_FALSE(std::isnan(b.score));
  EXPECT_THROW(screen.apply(cv::Mat(120, 200, CV_8UC1), table, &blobs), std::invalid_argument);
}

TEST(CandidateScreen, ColoursFileNamesTheVerifierAndMayTakeItsRangeFromIt) {
  const std::string dir = std::filesystem::path(testing::TempDir() + "/rle_vision_screen").lexically_normal().string();
  std::filesystem::create_directories(dir + "/models");
  BlobVerifier copy = BlobVerifier::load([&] {
    trainedVerifier()->save(dir + "/models/ball.yml");
    return dir + "/models/ball.yml";
  }());
  std::ofstream(dir + "/colors.yaml") << "classes:\n  - name: ball\n    verifier_file: models/ball.yml\n    min_score: 0.7\n"
                                         "  - name: goal\n    min: [0, 170, 0]\n    max: [255, 255, 110]\n";
  const std::vector<ColorClass> classes = loadColorClasses(dir + "/colors.yaml");
  ASSERT_EQ(classes.size(), 2u);
  EXPECT_EQ(classes[0].verifier_file, "models/ball.yml") << "as written";
  EXPECT_EQ(classes[0].verifier_path, dir + "/models/ball.yml") << "resolved against the colours file's folder";
  EXPECT_DOUBLE_EQ(classes[0].min_score, 0.7);
  EXPECT_EQ(classes[0].min, yellowRange().min) << "the range the verifier was trained on";
  EXPECT_EQ(classes[0].max, yellowRange().max);
  EXPECT_TRUE(classes[1].verifier_file.empty());
  const std::vector<ClassVerifier> verifiers = loadClassVerifiers(classes);
  ASSERT_EQ(verifiers.size(), 1u);
  EXPECT_EQ(verifiers[0].class_name, "ball");
  EXPECT_DOUBLE_EQ(verifiers[0].min_score, 0.7);
  // The written colours file reads back the same, the path still as written.
  std::ofstream(dir + "/written.yaml") << colorClassesToYaml(classes);
  EXPECT_EQ(colorClassesToYaml(classes).find(dir), std::string::npos) << "no path of this machine is written";
  const std::vector<ColorClass> again = loadColorClasses(dir + "/written.yaml");
  EXPECT_EQ(again[0].verifier_file, "models/ball.yml");
  EXPECT_EQ(again[0].verifier_path, classes[0].verifier_path);
  EXPECT_DOUBLE_EQ(again[0].min_score, 0.7);
  EXPECT_EQ(again[0].min, classes[0].min);
  // Refused with the reason: min_score alone, out of 0..1, a missing model, half a range, an
  // empty file name.
  const std::string bad[] = {"classes:\n  - name: b\n    min: [0,0,0]\n    max: [9,9,9]\n    min_score: 0.5\n",
                             "classes:\n  - name: b\n    verifier_file: models/ball.yml\n    min_score: 1.5\n",
                             "classes:\n  - name: b\n    verifier_file: models/none.yml\n",
                             "classes:\n  - name: b\n    verifier_file: models/ball.yml\n    min: [0,0,0]\n",
                             "classes:\n  - name: b\n    verifier_file: \"\"\n"};
  const std::string reasons[] = {"no verifier_file", "min_score", "takes its range from its verifier", "both 'min' and 'max'",
                                 "verifier_file is empty"};
  for (int i = 0; i < 5; ++i) {
    std::ofstream(dir + "/bad.yaml") << bad[i];
    try {
      loadColorClasses(dir + "/bad.yaml");
      ADD_FAILURE() << "accepted: " << bad[i];
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(reasons[i]), std::string::npos) << e.what();
    }
  }
  // A model named with a range given is only read when the verifiers are loaded.
  std::ofstream(dir + "/bad.yaml") << "classes:\n  - name: b\n    verifier_file: models/none.yml\n    min: [0,0,0]\n"
                                      "    max: [9,9,9]\n";
  EXPECT_THROW(loadClassVerifiers(loadColorClasses(dir + "/bad.yaml")), std::runtime_error);
}

// The model the package ships loads without the data it was trained on, small, for the ball.
// A verifier's model that only carries a floor guard scale (withFloorGuard reads nothing else).
ClassVerifier verifierWithScale(const std::string& class_name, double scale) {
  BlobVerifier model;
  model.setFloorGuardScale(scale);
  return {class_name, std::make_shared<const BlobVerifier>(std::move(model)), 0.5};
}

std::vector<std::string> namesOf(const std::vector<ColorClass>& classes) {
  std::vector<std::string> names;
  for (const ColorClass& c : classes) names.push_back(c.name);
  return names;
}

// The tracker's table with the floor's guard: the fringe (a strip beyond the floor's range) is the
// guard's, which yields no blob, and the ball at the strip's end is a blob of its own; without
// the guard it is one blob with the strip, centred off the ball.
TEST(FloorGuard, TheFloorsFringeIsTheGuardsAndTheBallAtItsEndABlobOfItsOwn) {
  const test::FringeScene scene = test::fringeScene();
  const ColorClass goal = blueRange();
  const std::vector<ColorClass> classes = {scene.floor, goal, scene.permissive};
  const std::vector<ColorClass> guarded = withFloorGuard(classes, {verifierWithScale("ball", 2.0)});
  ASSERT_EQ(namesOf(guarded), (std::vector<std::string>{"field", "goal", "floor_guard", "ball"}));
  const ColorClass& guard = guarded[2];
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(guard.min[c], scene.floor.min[c] - 15);  // half width 15 -> 30
    EXPECT_EQ(guard.max[c], scene.floor.max[c] + 15);
  }
  EXPECT_TRUE(guard.verifier_file.empty());
  // Again on its own output (a set coming back from active_color_ranges): the same.
  EXPECT_EQ(namesOf(withFloorGuard(guarded, {verifierWithScale("ball", 2.0)})), namesOf(guarded));
  // Scale 1, no field class, the field after the class, no room: no guard (and an old one goes).
  EXPECT_EQ(namesOf(withFloorGuard(guarded, {verifierWithScale("ball", 1.0)})), namesOf(classes));
  EXPECT_EQ(namesOf(withFloorGuard({goal, scene.permissive}, {verifierWithScale("ball", 2.0)})),
            (std::vector<std::string>{"goal", "ball"}));
  EXPECT_EQ(namesOf(withFloorGuard({scene.permissive, scene.floor}, {verifierWithScale("ball", 2.0)})),
            (std::vector<std::string>{"ball", "field"}));
  std::vector<ColorClass> full(kMaxColorClasses - 2, goal);
  full.insert(full.begin(), scene.floor);
  full.push_back(scene.permissive);
  EXPECT_EQ(withFloorGuard(full, {verifierWithScale("ball", 2.0)}).size(), full.size());

  // A lone image's floor colour: the field class's range, else a field class (no blob of its
  // own) just before the class with a verifier; nothing without one.
  ColorClass verified = scene.permissive;
  verified.verifier_file = "ball.yml";
  ColorClass configured_field = scene.floor;
  configured_field.min = configured_field.max = Channels{{0, 0, 0}};
  const std::vector<ColorClass> with_field = withFloorFirst({configured_field, goal, verified}, scene.floor);
  EXPECT_EQ(namesOf(with_field), (std::vector<std::string>{"field", "goal", "ball"}));
  EXPECT_EQ(with_field[0].min, scene.floor.min);
  EXPECT_EQ(with_field[0].max, scene.floor.max);
  const std::vector<ColorClass> inserted = withFloorFirst({goal, verified}, scene.floor);
  ASSERT_EQ(namesOf(inserted), (std::vector<std::string>{"goal", "field", "ball"}));
  EXPECT_EQ(inserted[1].min_area_px, std::numeric_limits<uint32_t>::max());
  EXPECT_EQ(namesOf(withFloorFirst({goal, scene.permissive}, scene.floor)), (std::vector<std::string>{"goal", "ball"}));

  cv::RNG rng(4);
  for (int frame = 0; frame < 10; ++frame) {
    const test::VerifierFrame f = test::drawFringeFrame(rng);
    for (const bool with_guard : {true, false}) {
      const ColorTable table(with_guard ? guarded : classes);
      ColorTracker tracker;
      std::vector<TrackedBlob> blobs;
      tracker.process(f.bgr, PixelFormat::BGR8, table, frame, &blobs);
      const int ball_label = with_guard ? 4 : 3;
      int on_strip_ball = 0, of_guard = 0;
      for (const TrackedBlob& b : blobs) {
        on_strip_ball += b.region.label == ball_label && inside(b, f.balls[0]);
        of_guard += with_guard && b.region.label == 3;
      }
      EXPECT_EQ(of_guard, 0) << "frame " << frame;
      EXPECT_EQ(on_strip_ball, with_guard ? 1 : 0) << "frame " << frame << (with_guard ? " with" : " without") << " the guard";
    }
  }
}

TEST(CandidateScreen, ShippedBallVerifierLoads) {
  const std::string path = test::sourcePath("config/ball_verifier.yml.gz");
  const BlobVerifier shipped = BlobVerifier::load(path);
  EXPECT_TRUE(shipped.trained());
  EXPECT_EQ(shipped.candidateRange().name, "ball");
  EXPECT_GE(shipped.modelCount(), 2);  // one per MSL date, each trained without it
  EXPECT_LT(std::filesystem::file_size(path), 200u * 1024u);
  // How it was made: the comment at the top of the compressed YAML.
  FILE* unzip = popen(("gzip -dc '" + path + "'").c_str(), "r");
  ASSERT_NE(unzip, nullptr);
  std::string text;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof(buffer), unzip)) > 0;) text.append(buffer, n);
  EXPECT_EQ(pclose(unzip), 0);
  EXPECT_NE(text.find("# Made by rle_vision_train --class ball"), std::string::npos) << "how it was made";
}

}  // namespace
}  // namespace rle_vision
