// The landmark step with known answers: eq. 4, drawn lines at every
// angle (including the parameterisation's boundaries), horizon merging and accuracy on the
// walking-gait simulator, determinism, false positives.
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "eval/line_matching.h"
#include "rle_vision/io/landmark_params_file.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;

TEST(RleHough, SampleCountFollowsThePapersEquations) {
  HoughOptions o;
  o.min_votes = 5;
  o.sampling_margin = 1;
  o.edge_width_px = 1;
  // A 320-px horizon among 1,000 edge pixels: 5 / 0.32^2 = 48.8 pairs.
  o.min_line_length_px = 320;
  EXPECT_EQ(RleHough::samplesFor(1000, o), 49u);
  // A 50-px line among the same 1,000 pixels: 5 / 0.05^2 = 2,000 pairs (a global Hough) ...
  o.min_line_length_px = 50;
  EXPECT_EQ(RleHough::samplesFor(1000, o), 2000u);
  // ... but a 30-px line inside its own 180-px object needs 5 / (30/180)^2 = 180.
  o.min_line_length_px = 30;
  EXPECT_EQ(RleHough::samplesFor(180, o), 180u);
}

struct DrawnLine {
  Segment segment;
  bool step_edge;  // the boundary of a filled half-plane strip, else a 1-px anti-aliased line
};

// One image per line, on a textured-free background; the line lies inside the image.
cv::Mat drawLine(const DrawnLine& d) {
  cv::Mat image(240, 320, CV_8UC3, cv::Scalar(40, 70, 40));
  const Segment& s = d.segment;
  if (d.step_edge) {
    // A filled quadrilateral whose one side is the segment: its edge is a step.
    const double nx = -(s.y2 - s.y1) / s.length(), ny = (s.x2 - s.x1) / s.length();
    const std::vector<cv::Point> quad = {
        cv::Point(cvRound(s.x1 * 256), cvRound(s.y1 * 256)), cv::Point(cvRound(s.x2 * 256), cvRound(s.y2 * 256)),
        cv::Point(cvRound((s.x2 + 40 * nx) * 256), cvRound((s.y2 + 40 * ny) * 256)),
        cv::Point(cvRound((s.x1 + 40 * nx) * 256), cvRound((s.y1 + 40 * ny) * 256))};
    cv::fillConvexPoly(image, quad, cv::Scalar(200, 200, 200), cv::LINE_AA, 8);
  } else {
    cv::line(image, cv::Point(cvRound(s.x1 * 16), cvRound(s.y1 * 16)), cv::Point(cvRound(s.x2 * 16), cvRound(s.y2 * 16)),
             cv::Scalar(220, 220, 220), 1, cv::LINE_AA, 4);
  }
  return image;
}

TEST(RleHough, FindsEveryDrawnLineAtEveryAngle) {
  // Every 3 degrees over (-90, 90], plus the boundaries of the parameterisation.
  std::vector<double> angles;
  for (double a = -87; a <= 90; a += 3) angles.push_back(a);
  for (double a : {-45.0, 45.0, 0.0, 90.0, -44.9, 44.9, 45.1, -45.1, 89.9, -89.9}) angles.push_back(a);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> length(30, 150), unit(0, 1);
  LandmarkDetector detector;
  LandmarkOptions options;
  int drawn = 0, found = 0;
  for (bool step : {false, true}) {
    for (double angle : angles) {
      const double len = length(rng), theta = angle * kDeg;
      // Centre placed so the segment and the step's strip stay inside the image.
      const double cx = 60 + unit(rng) * 200, cy = 60 + unit(rng) * 120;
      const Segment s{cx - 0.5 * len * std::cos(theta), cy - 0.5 * len * std::sin(theta),
                      cx + 0.5 * len * std::cos(theta), cy + 0.5 * len * std::sin(theta)};
      LandmarkResult result;
      detector.detectInImage(drawLine({s, step}), options, &result);
      ++drawn;
      const MatchScore score = scoreLines(result.lines, {s}, 1.0 * kDeg, 2.0);
      found += score.found;
      std::string detected;
      for (const DetectedLine& l : result.lines) {
        detected += cv::format(" [%.2f deg, c %.2f, %.1f px]", l.line.theta / kDeg, l.line.intercept, l.length);
      }
      EXPECT_EQ(score.found, 1) << (step ? "step edge" : "line") << " at " << angle << " deg, c "
                                << s.line().intercept << ", " << len << " px; detected:" << detected;
      // A 1-px line is one line; a step edge here is one side of a filled quadrilateral.
      EXPECT_LE(result.lines.size(), step ? 4u : 1u) << (step ? "step edge" : "line") << " at " << angle << " deg, "
                                                     << len << " px at " << cx << "," << cy << "; detected:" << detected;
    }
  }
  std::printf("[ drawn ] %d of %d lines found within 1 deg and 2 px\n", found, drawn);
}

TEST(RleHough, LineAtPlus45DegreesIsOneLineNotTwo) {
  // At +45 deg the intercept flips sign between conventions: votes land on both sides.
  LandmarkDetector detector;
  LandmarkResult result;
  const Segment s{100, 60, 200, 160};
  detector.detectInImage(drawLine({s, false}), LandmarkOptions(), &result);
  ASSERT_EQ(result.lines.size(), 1u);
  EXPECT_NEAR(result.lines[0].line.theta, M_PI / 4, 0.2 * kDeg);
  EXPECT_NEAR(result.lines[0].length, s.length(), 6.0);
}

TEST(RleHough, DeterministicForASeed) {
  const SimFrame frame = SceneSimulator(loadSceneConfig(test::sourcePath("config/scene_default.yaml"))).render(3, 0.1);
  LandmarkDetector a, b;
  LandmarkOptions options;
  LandmarkResult ra, rb;
  a.detectInImage(frame.image, options, &ra);
  b.detectInImage(frame.image, options, &rb);
  a.detectInImage(frame.image, options, &rb);  // and the same detector run twice
  ASSERT_EQ(ra.lines.size(), rb.lines.size());
  ASSERT_GT(ra.lines.size(), 10u);
  for (size_t i = 0; i < ra.lines.size(); ++i) {
    EXPECT_EQ(ra.lines[i].line.theta, rb.lines[i].line.theta);
    EXPECT_EQ(ra.lines[i].line.intercept, rb.lines[i].line.intercept);
    EXPECT_EQ(ra.lines[i].votes, rb.lines[i].votes);
  }
}

TEST(RleHough, AFramesWorkBudgetGoesToTheLongestLinesAndIsReported) {
  // Eight separate lines (each its own edge object), 40 to 180 px, shortest at the top.
  cv::Mat image(240, 320, CV_8UC3, cv::Scalar(40, 70, 40));
  std::vector<Segment> drawn;
  for (int i = 0; i < 8; ++i) {
    const double length = 40 + 20 * i, y = 20.5 + 27 * i;
    drawn.push_back(Segment{60, y, 60 + length, y + 0.1 * length});
    cv::line(image, cv::Point(cvRound(drawn.back().x1 * 16), cvRound(drawn.back().y1 * 16)),
             cv::Point(cvRound(drawn.back().x2 * 16), cvRound(drawn.back().y2 * 16)), cv::Scalar(220, 220, 220), 1,
             cv::LINE_AA, 4);
  }
  LandmarkDetector detector;
  LandmarkOptions options;
  LandmarkResult full;
  detector.detectInImage(image, options, &full);
  EXPECT_FALSE(full.hough.budget_exhausted);
  EXPECT_EQ(full.hough.objects_skipped, 0u);
  EXPECT_EQ(scoreLines(full.lines, drawn, 1.0 * kDeg, 2.0).found, 8);
  // Lines come out in the objects' order (top to bottom here), whatever order they were fitted in.
  for (size_t i = 1; i < full.lines.size(); ++i) EXPECT_LE(full.lines[i - 1].object, full.lines[i].object);

  // Exactly the fits it took: nothing cut.
  options.hough.max_refinements_per_frame = static_cast<int>(full.hough.candidates);
  LandmarkResult exact;
  detector.detectInImage(image, options, &exact);
  EXPECT_FALSE(exact.hough.budget_exhausted);
  EXPECT_EQ(exact.lines.size(), full.lines.size());

  // Half of them: the longest lines are found, each shorter one only if every longer one is,
  // and the objects not reached are counted.
  options.hough.max_refinements_per_frame = static_cast<int>(full.hough.candidates / 2);
  LandmarkResult cut;
  detector.detectInImage(image, options, &cut);
  EXPECT_TRUE(cut.hough.budget_exhausted);
  EXPECT_EQ(cut.hough.candidates, full.hough.candidates / 2);
  bool longer_found = true;
  int found = 0;
  for (int i = 7; i >= 0; --i) {
    const bool is_found = scoreLines(cut.lines, {drawn[i]}, 1.0 * kDeg, 2.0).found == 1;
    EXPECT_TRUE(!is_found || longer_found) << "the " << 40 + 20 * i << "-px line found before a longer one";
    longer_found = is_found;
    found += is_found;
  }
  EXPECT_GE(found, 2);
  EXPECT_LE(found, 6);
  EXPECT_GE(cut.hough.objects_skipped, static_cast<uint64_t>(8 - found - 1));
  EXPECT_EQ(cut.hough.objects + cut.hough.objects_skipped, 8u);
}

TEST(RleHough, NoLinesOnBlankImagesAndFewOnPureNoise) {
  LandmarkDetector detector;
  LandmarkResult result;
  detector.detectInImage(cv::Mat(480, 640, CV_8UC3, cv::Scalar(40, 140, 50)), LandmarkOptions(), &result);
  EXPECT_EQ(result.lines.size(), 0u);
  EXPECT_FALSE(result.horizon.found);
  // Gaussian noise, sigma 10 and 20 (the simulator uses 2): the documented false-positive rate
  // is at most one line per ten frames.
  for (double sigma : {10.0, 20.0}) {
    size_t lines = 0;
    for (int i = 0; i < 20; ++i) {
      cv::Mat noise(480, 640, CV_16SC3), image;
      cv::RNG(100 + i).fill(noise, cv::RNG::NORMAL, 0, sigma);
      cv::Mat(480, 640, CV_16SC3, cv::Scalar(100, 100, 100)).copyTo(image);
      image += noise;
      image.convertTo(image, CV_8UC3);
      detector.detectInImage(image, LandmarkOptions(), &result);
      lines += result.lines.size();
      EXPECT_FALSE(result.horizon.found);
    }
    std::printf("[ noise ] sigma %.0f: %zu lines in 20 frames\n", sigma, lines);
    EXPECT_LE(lines, 2u) << "sigma " << sigma;
  }
}

TEST(Horizon, CollinearPiecesMergeIntoOneLine) {
  // The paper's figure 3: a horizon broken into three pieces by obstacles, and a box edge.
  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(40, 140, 50));
  const double theta = -4 * kDeg;
  const ImageLine truth = lineThroughPointWithAngle(320, 150, theta);
  // Sky above the line.
  std::vector<cv::Point> sky = {{0, 0}, {639, 0}};
  for (int x : {639, 0}) sky.emplace_back(x, cvRound(truth.intercept + x * std::tan(theta)));
  cv::fillConvexPoly(image, sky, cv::Scalar(235, 205, 170), cv::LINE_AA);
  // Two boxes standing on the horizon cut it into three pieces.
  cv::rectangle(image, cv::Rect(150, 100, 60, 140), cv::Scalar(40, 40, 200), cv::FILLED);
  cv::rectangle(image, cv::Rect(400, 90, 80, 160), cv::Scalar(200, 50, 30), cv::FILLED);
  LandmarkDetector detector;
  LandmarkResult result;
  detector.detectInImage(image, LandmarkOptions(), &result);
  // From the lines alone (no region evidence).
  const HorizonEstimate h = findHorizon(result.lines, image.cols, image.rows, HorizonOptions());
  ASSERT_TRUE(h.found);
  EXPECT_GE(h.pieces, 3);
  EXPECT_NEAR(lineAngleDifference(h.line.theta, theta), 0.0, 0.2 * kDeg);
  EXPECT_NEAR(h.line.intercept, truth.intercept, 1.5);
  EXPECT_GT(h.coverage, 0.6);
  EXPECT_LT(h.coverage, 0.9);  // the boxes hide part of it
  EXPECT_GT(h.confidence, 0.5);
  // Its extent spans the image.
  EXPECT_LT(std::min(h.x1, h.x2), 20);
  EXPECT_GT(std::max(h.x1, h.x2), 620);
}

TEST(Horizon, NotFoundWithoutALongLevelLine) {
  std::vector<DetectedLine> lines(2);
  lines[0].line = lineThroughPoints(0, 0, 0, 100);  // vertical
  lines[0].x2 = 0;
  lines[0].y2 = 100;
  lines[0].length = 100;
  lines[1].line = lineThroughPoints(100, 50, 160, 50);  // level but short for a 640-px image
  lines[1].x1 = 100;
  lines[1].y1 = lines[1].y2 = 50;
  lines[1].x2 = 160;
  lines[1].length = 60;
  lines[1].sums.addRun(100, 160, 50);
  EXPECT_FALSE(findHorizon(lines, 640, 480, HorizonOptions()).found);
}

TEST(Horizon, AngleErrorOverTwoHundredWalkingGaitFrames) {
  SceneConfig scene = loadSceneConfig(test::sourcePath("config/scene_default.yaml"));
  scene.noise_sigma = 3;
  const SceneSimulator simulator(scene);
  LandmarkDetector detector;
  LandmarkResult result;
  std::vector<double> angle_errors, roll_errors, pitch_errors;
  int found = 0;
  for (int frame = 0; frame < 200; ++frame) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    detector.detectInImage(f.image, LandmarkOptions(), &result);
    if (!result.horizon.found) continue;
    ++found;
    angle_errors.push_back(lineAngleDifference(result.horizon.line.theta, f.horizon.theta) / kDeg);
    double roll, pitch;
    horizonAttitude(result.horizon.line, &simulator.camera(), &roll, &pitch);
    roll_errors.push_back(std::fabs(roll - f.pose.roll) / kDeg);
    pitch_errors.push_back(std::fabs(pitch - f.pose.pitch) / kDeg);
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  EXPECT_GE(found, 198);
  EXPECT_LT(median(angle_errors), 0.5);
  EXPECT_LT(median(roll_errors), 0.5);
  EXPECT_LT(median(pitch_errors), 0.5);
  std::printf("[ horizon ] found in %d/200 frames; median errors: angle %.3f deg, roll %.3f deg, pitch %.3f deg\n",
              found, median(angle_errors), median(roll_errors), median(pitch_errors));
}

// --print-params writes every parameter of the table at its default; reading it back gives
// the defaults, and the shipped file (all defaults) reads.
TEST(LandmarkParams, DefaultsFileRoundTripsEveryParameter) {
  const std::string text = defaultLandmarkParamsYaml();
  const LandmarkOptions file = parseLandmarkParams(text, "defaults.yaml");
  const LearningOptions learning = parseLearningParams(text, "defaults.yaml");
  const FieldOptions field = parseFieldParams(text, "defaults.yaml");
  const LandmarkOptions defaults;
  const LearningOptions learning_defaults;
  const FieldOptions field_defaults;
  int keys = 0;
#define RLE_EXPECT_READ_BACK(key, read, expected)              \
  EXPECT_EQ(read, expected) << #key;                            \
  EXPECT_NE(text.find(#key ": "), std::string::npos) << #key;   \
  ++keys;
#define RLE_EDGE_PARAM(key, member, type, d, min, max, doc) RLE_EXPECT_READ_BACK(key, file.member, defaults.member)
#define RLE_OBJECTS_PARAM(key, member, type, d, min, max, doc) \
  RLE_EXPECT_READ_BACK(key, file.objects.member, defaults.objects.member)
#define RLE_HOUGH_PARAM(key, member, type, d, min, max, doc) RLE_EXPECT_READ_BACK(key, file.hough.member, defaults.hough.member)
#define RLE_HORIZON_PARAM(key, member, type, d, min, max, doc) \
  RLE_EXPECT_READ_BACK(key, file.horizon.member, defaults.horizon.member)
#define RLE_LEARNING_PARAM(key, member, type, d, min, max, doc) \
  RLE_EXPECT_READ_BACK(key, learning.member, learning_defaults.member)
#define RLE_FIELD_COLOR_PARAM(key, member, type, d, min, max, doc) \
  RLE_EXPECT_READ_BACK(key, field.colour.member, field_defaults.colour.member)
#define RLE_FIELD_BOUNDARY_PARAM(key, member, type, d, min, max, doc) \
  RLE_EXPECT_READ_BACK(key, field.boundary.member, field_defaults.boundary.member)
#include "rle_vision/params/landmark_params.def"
#undef RLE_EXPECT_READ_BACK
  EXPECT_EQ(keys, 54 + 15);
  // Values that differ from the defaults are read, too.
  EXPECT_EQ(parseLandmarkParams("gray_threshold: 40\nthin_edges: false\nseed: 7\n", "l.yaml").objects.gray_threshold, 40);
  EXPECT_EQ(parseLandmarkParams("seed: 7\n", "l.yaml").hough.seed, 7u);
  EXPECT_FALSE(parseLandmarkParams("thin_edges: false\n", "l.yaml").objects.thin);
  EXPECT_NO_THROW(loadLandmarkParams(test::sourcePath("config/landmark.yaml")));
  EXPECT_NO_THROW(loadLearningParams(test::sourcePath("config/landmark.yaml")));
}

TEST(LandmarkParams, LearningKeysAreCheckedLikeTheOthers) {
  EXPECT_EQ(parseLearningParams("learning_blend: 0.5\nlearning_create_classes: true\n", "l.yaml").blend, 0.5);
  EXPECT_TRUE(parseLearningParams("learning_create_classes: true\n", "l.yaml").create_classes);
  EXPECT_THROW(parseLearningParams("learning_blend: .nan\n", "l.yaml"), ConfigError);
  EXPECT_THROW(parseLearningParams("learning_blend: 0\n", "l.yaml"), ConfigError);
  EXPECT_THROW(parseLearningParams("learning_create_classes: maybe\n", "l.yaml"), ConfigError);
  EXPECT_THROW(parseLearningParams("learning_blnd: 0.3\n", "l.yaml"), ConfigError);
}

TEST(LandmarkParams, FieldKeysAreCheckedLikeTheOthers) {
  const FieldOptions read = parseFieldParams("field_blend: 0.5\nfield_column_step_px: 2\n", "l.yaml");
  EXPECT_EQ(read.colour.blend, 0.5);
  EXPECT_EQ(read.boundary.column_step_px, 2);
  EXPECT_TRUE(parseLearningLoopParams("learning_field_class: true\n", "l.yaml").field_class);
  EXPECT_THROW(parseFieldParams("field_inlier_px: .nan\n", "l.yaml"), ConfigError);
  EXPECT_THROW(parseFieldParams("field_column_step_px: 0\n", "l.yaml"), ConfigError);
  EXPECT_THROW(parseFieldParams("field_column_step_px: 2.5\n", "l.yaml"), ConfigError);
  EXPECT_THROW(parseFieldParams("field_blnd: 0.3\n", "l.yaml"), ConfigError);
}

TEST(LandmarkParams, BrokenFilesFailWithTheLine) {
  try {
    parseLandmarkParams("min_votes: 5\nfit_distanse_px: 3\n", "l.yaml");
    FAIL() << "typo accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("l.yaml:2: unknown key 'fit_distanse_px'"), std::string::npos);
  }
  try {
    parseLandmarkParams("gray_threshold: 100\nsharp_threshold: 50\n", "l.yaml");
    FAIL() << "sharp below gray accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("sharp_threshold must be >= gray_threshold"), std::string::npos);
  }
  // The adaptive gray band's floor above its ceiling: refused only when adaptive_edges is on.
  EXPECT_THROW(parseLandmarkParams("adaptive_edges: true\ngray_threshold: 40\nedge_min_value: 50\n", "l.yaml"), ConfigError);
  EXPECT_NO_THROW(parseLandmarkParams("gray_threshold: 40\nedge_min_value: 50\n", "l.yaml"));
  EXPECT_THROW(parseLandmarkParams("edge_gain: .nan\n", "l.yaml"), ConfigError);
  EXPECT_THROW(parseLandmarkParams("min_votes: 5.5\n", "l.yaml"), ConfigError);  // a count is whole
  EXPECT_THROW(parseLandmarkParams("theta_bin_deg: 20\n", "l.yaml"), ConfigError);  // beyond the table's limit
}

}  // namespace
}  // namespace rle_vision

namespace rle_vision {
namespace {

// Three boxes well apart (no occlusion, no edge shared between boxes), the gait swaying.
SceneConfig threeBoxScene() {
  SceneConfig scene = loadSceneConfig(test::sourcePath("config/scene_default.yaml"));
  scene.boxes.resize(3);
  scene.boxes[0] = SceneBox{"a", "red", {{210, 40, 40}}, 1.3, 0.45, 0.25, 0.25, 0.3, 25, 0, 0, 0, 0, 0};
  scene.boxes[1] = SceneBox{"b", "blue", {{30, 50, 200}}, 1.8, -0.35, 0.3, 0.3, 0.35, -10, 0, 0, 0, 0, 0};
  scene.boxes[2] = SceneBox{"c", "yellow", {{230, 200, 40}}, 2.6, 0.05, 0.3, 0.3, 0.3, 40, 0, 0, 0, 0, 0};
  return scene;
}

// A 5x5 filter cannot separate edges closer than its support: a box's top face seen at a
// grazing angle is a sliver whose two long edges make one ridge. Such edges (another edge
// within 4 px along them, at an angle under 10 deg) are left out of what must be found.
bool resolvable(const EdgeTruth& e, const std::vector<EdgeTruth>& all) {
  const Segment t{e.x1, e.y1, e.x2, e.y2};
  for (const EdgeTruth& other : all) {
    if (&other == &e) continue;
    const Segment o{other.x1, other.y1, other.x2, other.y2};
    if (o.length() < 5 || lineAngleDifference(o.line().theta, t.line().theta) > 10 * kDeg) continue;
    // The other edge runs within 4 px of this one somewhere along it.
    for (double f = 0; f <= 1.0; f += 0.25) {
      const double x = o.x1 + f * (o.x2 - o.x1), y = o.y1 + f * (o.y2 - o.y1);
      const double along = ((x - t.x1) * (t.x2 - t.x1) + (y - t.y1) * (t.y2 - t.y1)) / (t.length() * t.length());
      if (along > 0 && along < 1 && std::fabs(signedDistance(t.line(), x, y)) < 4) return false;
    }
  }
  return true;
}

TEST(RleHough, FindsSimulatedEdgesOfThirtyPixelsOrMore) {
  const SceneSimulator simulator(threeBoxScene());
  LandmarkDetector detector;
  LandmarkResult result;
  int truths = 0, found = 0;
  for (int frame = 0; frame < 30; frame += 3) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    detector.detectInImage(f.image, LandmarkOptions(), &result);
    for (const EdgeTruth& e : f.edges) {
      const Segment t{e.x1, e.y1, e.x2, e.y2};
      if (t.length() < 30 || !resolvable(e, f.edges)) continue;
      ++truths;
      const bool ok = scoreLines(result.lines, {t}, 1.0 * kDeg, 2.0).found == 1;
      found += ok;
      if (!ok) {
        std::printf("[ simulated ] missed in frame %d: %s at %.2f deg, c %.2f, %.0f px\n", frame,
                    e.box < 0 ? "horizon" : "box edge", t.line().theta / kDeg, t.line().intercept, t.length());
      }
    }
  }
  std::printf("[ simulated ] %d of %d edges >= 30 px found within 1 deg and 2 px\n", found, truths);
  EXPECT_GT(truths, 100);
  // The accuracy target on simulator ground truth (docs/ARCHITECTURE.md): line recall >= 0.95.
  EXPECT_GE(static_cast<double>(found) / truths, 0.95);
}

}  // namespace
}  // namespace rle_vision
