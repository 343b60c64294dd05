// The field colour and the field boundary with known answers: a drawn hall (a carpet with white
// lines, robots standing across its far edge, people and a wall beyond it) whose boundary is an
// exact polyline; a frame with no floor; a light drift the field colour must follow.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/field/field_boundary.h"
#include "rle_vision/field/field_color.h"
#include "rle_vision/field/field_detector.h"
#include "rle_vision/field/on_field.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"
#include "rle_vision/sim/sensor_noise.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

constexpr int kWidth = 640, kHeight = 480;
const cv::Scalar kCarpet(55, 135, 45);  // BGR

// The true boundary: a corner of the field, left edge rising to the corner, right edge falling.
double trueRow(double x) { return x <= 420 ? 210 - 70 * x / 420 : 140 + 80 * (x - 420) / 220; }

// The hall at light gain `gain`: wall and stands above the field edge, the carpet below it with
// white lines and +-10% blotches, two robots standing across the edge, a person's skin and a
// green banner beyond it. `carpet` (if given): CV_8UC1, 255 where the carpet itself shows.
cv::Mat drawHall(double gain, uint32_t seed, cv::Mat* carpet = nullptr) {
  cv::Mat image(kHeight, kWidth, CV_8UC3, cv::Scalar(150, 170, 185));  // a beige wall
  cv::rectangle(image, cv::Rect(0, 0, kWidth, 90), cv::Scalar(70, 60, 60), cv::FILLED);  // dark stands
  std::vector<cv::Point> field = {{0, 210 * 16}, {420 * 16, 140 * 16}, {kWidth * 16, 220 * 16},
                                  {kWidth * 16, kHeight * 16}, {0, kHeight * 16}};
  cv::fillPoly(image, std::vector<std::vector<cv::Point>>{field}, kCarpet, cv::LINE_AA, 4);
  // Seeded, so a test's frames do not depend on which tests ran before it (cv::theRNG is global).
  cv::Mat blotches(kHeight / 8, kWidth / 8, CV_32F);
  cv::RNG(seed).fill(blotches, cv::RNG::UNIFORM, 0.9, 1.1);
  cv::resize(blotches, blotches, image.size(), 0, 0, cv::INTER_LINEAR);
  for (int r = 0; r < kHeight; ++r) {
    for (int x = 0; x < kWidth; ++x) {
      if (r > trueRow(x) + 1) image.at<cv::Vec3b>(r, x) *= blotches.at<float>(r, x);
    }
  }
  // Field lines: thin white stripes on the carpet (they must not end the field).
  cv::line(image, {0, 330}, {kWidth, 300}, cv::Scalar(235, 235, 235), 6, cv::LINE_AA);
  cv::line(image, {300, kHeight}, {380, 190}, cv::Scalar(235, 235, 235), 5, cv::LINE_AA);
  // Robots standing on the field across its far edge (black bodies), a person beyond it.
  cv::rectangle(image, cv::Rect(120, 120, 60, 110), cv::Scalar(30, 30, 30), cv::FILLED);
  cv::rectangle(image, cv::Rect(500, 110, 50, 120), cv::Scalar(25, 25, 35), cv::FILLED);
  cv::ellipse(image, {260, 110}, {14, 18}, 0, 0, 360, cv::Scalar(140, 170, 220), cv::FILLED);
  cv::rectangle(image, cv::Rect(330, 40, 60, 20), cv::Scalar(50, 140, 50), cv::FILLED);  // a green banner
  if (carpet) {
    // Carpet pixels, 2 px clear of every other colour's edge (anti-aliased edges are mixtures).
    cv::Mat is_carpet(image.size(), CV_8UC1, cv::Scalar(0));
    cv::fillPoly(is_carpet, std::vector<std::vector<cv::Point>>{field}, cv::Scalar(255), cv::LINE_8, 4);
    cv::line(is_carpet, {0, 330}, {kWidth, 300}, cv::Scalar(0), 6 + 4);
    cv::line(is_carpet, {300, kHeight}, {380, 190}, cv::Scalar(0), 5 + 4);
    cv::rectangle(is_carpet, cv::Rect(118, 118, 64, 114), cv::Scalar(0), cv::FILLED);
    cv::rectangle(is_carpet, cv::Rect(498, 108, 54, 124), cv::Scalar(0), cv::FILLED);
    cv::erode(is_carpet, *carpet, cv::Mat::ones(5, 5, CV_8U));
  }
  image.convertTo(image, -1, gain);
  addGaussianNoise(3.0, seed, &image);  // the simulator's sensor noise
  return image;
}

FieldBoundaryEstimate boundaryOf(const cv::Mat& bgr, FieldColor* colour) {
  const cv::Mat yuv = fieldYuv(bgr);
  *colour = FieldColorModel().seed(yuv);
  if (!colour->found) return FieldBoundaryEstimate();
  return FieldBoundaryFinder().find(FieldColorModel::mask(yuv, colour->range));
}

TEST(FieldBoundary, FollowsTheFieldsEdgeOverLinesRobotsAndPeople) {
  FieldColor colour;
  const FieldBoundaryEstimate boundary = boundaryOf(drawHall(1.0, 1), &colour);
  ASSERT_TRUE(colour.found);
  EXPECT_GT(colour.share, 0.8);
  ASSERT_TRUE(boundary.found);
  EXPECT_GT(boundary.confidence, 0.6);
  // A corner: two segments (three points), not more.
  EXPECT_LE(boundary.polyline.size(), 4u);
  std::vector<double> errors;
  for (int x = 2; x < kWidth - 2; ++x) errors.push_back(std::fabs(boundary.rowAt(x) - trueRow(x)));
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], worst = errors.back();
  for (const cv::Point2f& p : boundary.polyline) std::printf("(%.0f,%.1f;%.1f) ", p.x, p.y, trueRow(p.x));
  std::printf("[ field ] boundary error: median %.2f px, worst %.2f px, confidence %.2f, %zu points\n", median, worst,
              boundary.confidence, boundary.polyline.size());
  EXPECT_LE(median, 2.0);
  EXPECT_LE(worst, 6.0);
  // Objects: a robot's feet on the field, the person's chin and the banner above the boundary.
  EXPECT_LT(boundary.heightAbove(150, 229), 0);
  EXPECT_GT(boundary.heightAbove(260, 128), 30);
  EXPECT_GT(boundary.heightAbove(360, 60), 60);
}

TEST(FieldDetector, AStreamSeedsOnceAndFindsTheEdgeFromTheScannedColumns) {
  // The scanned columns' YUV is the full conversion's, column for column.
  const cv::Mat hall = drawHall(1.0, 1);
  const cv::Mat full = fieldYuv(hall), columns = fieldYuvColumns(hall, 2, 4);
  ASSERT_EQ(columns.cols, kWidth / 4);
  for (int j = 0; j < columns.cols; j += 7) {
    EXPECT_EQ(cv::norm(full.col(2 + 4 * j), columns.col(j), cv::NORM_INF), 0) << "column " << j;
  }
  FieldDetector detector;
  for (int frame = 0; frame < 5; ++frame) {
    FieldResult result;
    detector.detect(drawHall(1.0 - 0.02 * frame, frame + 1), &result);
    EXPECT_EQ(result.reseeded, frame == 0);
    ASSERT_TRUE(result.boundary.found) << "frame " << frame;
    double worst = 0;
    for (int x = 2; x < kWidth - 2; ++x) worst = std::max(worst, std::fabs(result.boundary.rowAt(x) - trueRow(x)));
    EXPECT_LE(worst, 6.0) << "frame " << frame;
  }
  FieldResult none;
  detector.detect(cv::Mat(), &none);
  EXPECT_FALSE(none.boundary.found);
}

// A configured floor colour seeds the stream when it covers the bottom of the view; one for
// another hall does not, and the view's own dominant colour is taken instead.
TEST(FieldDetector, SeedsFromAConfiguredColourOnlyWhereItIsTheFloor) {
  const cv::Mat hall = drawHall(1.0, 3);
  FieldResult seeded;
  FieldDetector().detect(hall, &seeded);
  ASSERT_TRUE(seeded.colour.found);
  ColorClass configured = seeded.colour.range;  // the carpet's own range, widened a little
  for (int c = 0; c < 3; ++c) {
    configured.min[c] = static_cast<uint8_t>(std::max(0, configured.min[c] - 5));
    configured.max[c] = static_cast<uint8_t>(std::min(255, configured.max[c] + 5));
  }
  FieldDetector from_file;
  from_file.setConfiguredColour(configured);
  FieldResult result;
  from_file.detect(hall, &result);
  ASSERT_TRUE(result.reseeded);
  ASSERT_TRUE(result.boundary.found);
  EXPECT_EQ(result.colour.range.min, configured.min);  // the seed is the configured range
  EXPECT_EQ(result.colour.range.max, configured.max);
  EXPECT_NEAR(result.boundary.rowAt(600), trueRow(600), 6.0);
  // Another hall's blue floor: not this view's floor, so the view seeds itself.
  ColorClass blue = test::makeClass("field", ColorSpace::YUV, {{20, 160, 60}}, {{120, 230, 120}});
  FieldDetector wrong_file;
  wrong_file.setConfiguredColour(blue);
  wrong_file.detect(hall, &result);
  ASSERT_TRUE(result.boundary.found);
  EXPECT_EQ(result.colour.range.min, seeded.colour.range.min);
  // Options come from the parameter table, with its limits.
  EXPECT_EQ(validateFieldOptions(FieldOptions()), "");
  FieldOptions bad;
  bad.boundary.inlier_px = NAN;
  EXPECT_NE(validateFieldOptions(bad).find("field_inlier_px"), std::string::npos);
  bad = FieldOptions();
  bad.colour.blend = 1.5;
  EXPECT_NE(validateFieldOptions(bad).find("field_blend"), std::string::npos);
}

TEST(FieldBoundary, MatchesTheSimulatedHallsExactBoundaryThroughAWalkingGait) {
  // config/scene_field.yaml: a carpet with white lines 0.7 m inside its edges, the hall's floor
  // around it, walls and people beyond, two robots standing at the far edge; the camera sways
  // with a biped's gait. SimFrame::field_top is the exact boundary per column.
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_field.yaml")));
  FieldDetector detector;
  std::vector<double> errors;
  int found = 0;
  for (int frame = 0; frame < 60; ++frame) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    FieldResult result;
    detector.detect(f.image, &result);
    found += result.boundary.found;
    for (int u = 0; u < f.image.cols && result.boundary.found; ++u) {
      if (!std::isnan(f.field_top[u])) errors.push_back(std::fabs(result.boundary.rowAt(u) - f.field_top[u]));
    }
  }
  ASSERT_EQ(found, 60);
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], worst = errors.back();
  std::printf("[ field ] simulated hall, 60 gait frames: median error %.2f px, 95%% %.2f px, worst %.2f px\n", median,
              errors[errors.size() * 95 / 100], worst);
  EXPECT_LE(median, 2.0);
  EXPECT_LE(worst, 6.0);
}

TEST(FieldBoundary, NoneWithoutAFloorInView) {
  // Four colours side by side at the bottom: no dominant floor colour.
  cv::Mat wall(kHeight, kWidth, CV_8UC3, cv::Scalar(150, 170, 185));
  const cv::Scalar colours[] = {{40, 40, 200}, {200, 60, 40}, {60, 200, 200}, {120, 120, 120}};
  for (int i = 0; i < 4; ++i) cv::rectangle(wall, cv::Rect(i * kWidth / 4, 0, kWidth / 4, kHeight), colours[i], cv::FILLED);
  FieldColor colour;
  EXPECT_FALSE(boundaryOf(wall, &colour).found);
  EXPECT_FALSE(colour.found);
  EXPECT_NEAR(colour.share, 0.25, 0.05);
  // A floor that fills the whole view has no edge in it: found, at the top row, or none; never
  // a boundary in the middle of the view.
  cv::Mat floor(kHeight, kWidth, CV_8UC3, kCarpet);
  const FieldBoundaryEstimate all_floor = boundaryOf(floor, &colour);
  EXPECT_TRUE(colour.found);
  if (all_floor.found) EXPECT_LE(all_floor.rowAt(kWidth / 2), 1.0);
  // An empty or wrong image: nothing, no crash.
  EXPECT_FALSE(FieldBoundaryFinder().find(cv::Mat()).found);
  EXPECT_FALSE(FieldBoundaryFinder().find(cv::Mat(10, 10, CV_8UC3, cv::Scalar::all(0))).found);
  EXPECT_FALSE(FieldColorModel().seed(cv::Mat()).found);
}

TEST(FieldColor, FollowsTheLightWhereAFixedRangeLosesTheFloor) {
  // The light falls to 55% over 40 frames: the field colour, updated on each frame's field
  // (below the boundary), keeps the carpet's pixels; the seed's fixed range does not.
  FieldColorModel model;
  FieldColor colour = model.seed(fieldYuv(drawHall(1.0, 1)));
  ASSERT_TRUE(colour.found);
  const FieldColor fixed = colour;
  double worst_kept = 1, fixed_last = 1;
  for (int frame = 1; frame <= 40; ++frame) {
    cv::Mat floor;  // the carpet's own pixels, for scoring
    const cv::Mat yuv = fieldYuv(drawHall(1.0 - 0.45 * frame / 40, frame + 1, &floor));
    const FieldBoundaryEstimate boundary = FieldBoundaryFinder().find(FieldColorModel::mask(yuv, colour.range));
    ASSERT_TRUE(boundary.found) << "frame " << frame;
    cv::Mat below(yuv.size(), CV_8UC1, cv::Scalar(0));
    for (int x = 0; x < kWidth; ++x) {
      const int top = std::max(0, static_cast<int>(std::ceil(boundary.rowAt(x))) + 2);
      if (top < kHeight) below(cv::Range(top, kHeight), cv::Range(x, x + 1)) = 255;
    }
    colour = model.update(colour, yuv, below);
    auto kept = [&](const ColorClass& range) {
      cv::Mat in = FieldColorModel::mask(yuv, range) & floor;
      return static_cast<double>(cv::countNonZero(in)) / cv::countNonZero(floor);
    };
    worst_kept = std::min(worst_kept, kept(colour.range));
    fixed_last = kept(fixed.range);
  }
  std::printf("[ field ] through the drift: worst share of the floor kept %.3f (a fixed range at the end: %.3f)\n",
              worst_kept, fixed_last);
  EXPECT_GE(worst_kept, 0.95);
  EXPECT_LT(fixed_last, 0.5);
}

TEST(FieldBoundary, OcclusionsBridgedCornersKept) {
  // A dip three entries wide (a robot in front of the edge) is bridged by a window of five; the
  // corner (a peak, rows 100 -> 80 -> 100) stays; a straight run simplifies to its ends.
  std::vector<float> rows = {100, 96, 92, 140, 140, 140, 80, 84, 88, 92, 96, 100};
  passOverOcclusions(&rows, 5);
  const std::vector<float> expected = {100, 96, 92, 92, 92, 92, 80, 84, 88, 92, 96, 100};
  EXPECT_EQ(rows, expected);
  // A robot in front of a sloping edge: joined straight between its sides, not flat.
  std::vector<float> sloped = {100, 98, 96, 140, 140, 140, 88, 86, 84};
  bridgeOcclusions(&sloped, 5, 4.0);
  const std::vector<float> joined = {100, 98, 96, 94, 92, 90, 88, 86, 84};
  EXPECT_EQ(sloped, joined);
  // A robot at the right end of the view (a step down, no far side) is held at the row before
  // it; a continuous slope at the left end stays.
  std::vector<float> end = {120, 112, 104, 100, 100, 100, 160, 161, 162};
  bridgeEndOcclusions(&end, 16, 0.5);
  const std::vector<float> held = {120, 112, 104, 100, 100, 100, 100, 100, 100};
  EXPECT_EQ(end, held);
  const std::vector<cv::Point2f> line = simplifyPolyline({{0, 0}, {10, 1}, {20, 2.2f}, {30, 3}}, 0.5);
  ASSERT_EQ(line.size(), 2u);
  EXPECT_EQ(line.back(), cv::Point2f(30, 3));
}

TEST(OnFieldFilter, DropsRequiredClassesBeyondTheBoundaryOnly) {
  const ColorTable table({test::makeClass("ball", ColorSpace::YUV, {{150, 60, 120}}, {{255, 120, 180}}),
                          test::makeClass("robot", ColorSpace::YUV, {{0, 0, 0}}, {{60, 255, 255}})});
  FieldBoundaryEstimate boundary;
  boundary.found = true;
  boundary.polyline = {{0, 100}, {200, 100}, {400, 60}};  // level, then rising to the right
  auto blob = [](int label, double cx, int bottom) {
    TrackedBlob b;
    b.region.label = label;
    b.region.cx = cx;
    b.region.bottom_at_cx = bottom;
    return b;
  };
  // Balls: on the field, 5 px above (within the 10-px margin), 20 px above (dropped), and on the
  // rising part 10 px below it; a robot far above (not a required class: kept).
  std::vector<TrackedBlob> blobs = {blob(1, 50, 120), blob(1, 60, 95), blob(1, 70, 80), blob(1, 300, 90),
                                    blob(2, 80, 40)};
  const OnFieldFilter filter(" ball , bal", 10.0);
  EXPECT_EQ(filter.unknownClasses(table), std::vector<std::string>{"bal"});
  std::vector<double> above;
  EXPECT_EQ(filter.apply(boundary, table, &blobs, &above), 1);
  ASSERT_EQ(blobs.size(), 4u);
  ASSERT_EQ(above.size(), 4u);
  EXPECT_DOUBLE_EQ(above[0], -20);
  EXPECT_DOUBLE_EQ(above[1], 5);
  EXPECT_EQ(blobs[2].region.cx, 300);
  EXPECT_DOUBLE_EQ(above[2], -10);
  EXPECT_DOUBLE_EQ(above[3], 60);
  // Without a boundary nothing is dropped and nothing is known.
  std::vector<TrackedBlob> again = {blob(1, 70, 80)};
  EXPECT_EQ(filter.apply(FieldBoundaryEstimate(), table, &again, &above), 0);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_TRUE(std::isnan(above[0]));
  EXPECT_TRUE(OnFieldFilter("", 10).empty());
}

}  // namespace
}  // namespace rle_vision
