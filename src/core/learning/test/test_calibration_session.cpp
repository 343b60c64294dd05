// Interactive calibration's state and picture: boxes re-measure the class, undo, the colour
// space switch, the mask and its counts, saving into colours files, and the window's picture.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/io/color_config.h"
#include "rle_vision/learning/calibration_session.h"
#include "rle_vision/learning/calibration_view.h"

namespace rle_vision {
namespace {

const cv::Scalar kCarpet(40, 150, 40), kBall(60, 170, 235), kRobot(20, 20, 20);
const cv::Point kCentre(120, 90);
const int kRadius = 14;

// A noisy carpet with an orange ball at kCentre and a black robot; `ball` is its exact mask.
cv::Mat scene(cv::Mat* ball, uint64_t seed) {
  cv::Mat image(180, 240, CV_8UC3, kCarpet);
  cv::rectangle(image, cv::Rect(20, 30, 40, 90), kRobot, cv::FILLED);
  *ball = cv::Mat::zeros(image.size(), CV_8UC1);
  cv::circle(*ball, kCentre, kRadius, 255, cv::FILLED, cv::LINE_8);
  image.setTo(kBall, *ball);
  cv::Mat noise(image.size(), CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 3);
  cv::Mat noisy;
  cv::add(image, noise, noisy);  // non-negative noise keeps the test simple: a shift of ~2
  return noisy;
}

const cv::Rect kBallBox(kCentre.x - kRadius - 4, kCentre.y - kRadius - 4, 2 * kRadius + 9, 2 * kRadius + 9);

CalibrationSession session() { return CalibrationSession("ball", CalibrationOptions()); }

TEST(CalibrationSession, ADraggedBoxGivesAClassWhoseMaskIsTheBall) {
  cv::Mat ball;
  const cv::Mat image = scene(&ball, 1);
  CalibrationSession s = session();
  const int frame = s.addFrame(image, "one");
  EXPECT_FALSE(s.result().has_value());
  EXPECT_EQ(cv::countNonZero(s.classMask(image)), 0) << "no class, no mask";
  ASSERT_TRUE(s.addBox(frame, kBallBox));
  ASSERT_TRUE(s.result().has_value()) << s.lastError();
  EXPECT_EQ(s.result()->color_class.name, "ball");
  const cv::Mat mask = s.classMask(image);
  cv::Mat on_ball;
  cv::bitwise_and(mask, ball, on_ball);
  EXPECT_GE(cv::countNonZero(on_ball), 0.95 * cv::countNonZero(ball));
  EXPECT_EQ(cv::countNonZero(mask) - cv::countNonZero(on_ball), 0) << "the carpet or the robot got in";
  const MaskCounts counts = CalibrationSession::countMask(mask, s.frame(frame).boxes);
  EXPECT_EQ(counts.in_boxes_px, cv::countNonZero(on_ball));
  EXPECT_EQ(counts.outside_px, 0);
  EXPECT_EQ(counts.box_area_px, kBallBox.area());
}

TEST(CalibrationSession, AClickIsNotABoxAndBoxesAreClippedToTheFrame) {
  cv::Mat ball;
  CalibrationSession s = session();
  const int frame = s.addFrame(scene(&ball, 2), "one");
  EXPECT_FALSE(s.addBox(frame, cv::Rect(50, 50, 1, 1)));
  EXPECT_FALSE(s.addBox(frame, cv::Rect(300, 300, 20, 20))) << "entirely outside the 240x180 frame";
  EXPECT_EQ(s.boxCount(), 0);
  ASSERT_TRUE(s.addBox(frame, cv::Rect(200, 150, 100, 100)));
  EXPECT_EQ(s.frame(frame).boxes.back(), cv::Rect(200, 150, 40, 30));
}

TEST(CalibrationSession, UndoTakesBackTheLastBoxAndItsClass) {
  cv::Mat ball;
  CalibrationSession s = session();
  const int first = s.addFrame(scene(&ball, 3), "one");
  const int second = s.addFrame(scene(&ball, 4), "two");
  EXPECT_FALSE(s.undo());
  ASSERT_TRUE(s.addBox(first, kBallBox));
  ASSERT_TRUE(s.addBox(second, kBallBox));
  EXPECT_EQ(s.boxCount(), 2);
  ASSERT_TRUE(s.undo());
  EXPECT_TRUE(s.frame(second).boxes.empty()) << "the most recent box goes first";
  EXPECT_EQ(s.frame(first).boxes.size(), 1u);
  EXPECT_TRUE(s.result().has_value());
  ASSERT_TRUE(s.undo());
  EXPECT_FALSE(s.result().has_value());
  EXPECT_TRUE(s.lastError().empty());
}

TEST(CalibrationSession, ABoxOverPlainCarpetSaysWhyThereIsNoClass) {
  cv::Mat ball;
  CalibrationSession s = session();
  const int frame = s.addFrame(scene(&ball, 5), "one");
  ASSERT_TRUE(s.addBox(frame, cv::Rect(150, 20, 40, 30)));
  EXPECT_FALSE(s.result().has_value());
  EXPECT_NE(s.lastError().find("object pixels"), std::string::npos) << s.lastError();
  const std::vector<std::string> status = calibrationStatus(s, MaskCounts());
  EXPECT_NE(status.front().find("no class"), std::string::npos) << status.front();
}

TEST(CalibrationSession, SwitchingTheColourSpaceRemeasuresTheClassInIt) {
  cv::Mat ball;
  const cv::Mat image = scene(&ball, 6);
  CalibrationSession s = session();
  ASSERT_TRUE(s.addBox(s.addFrame(image, "one"), kBallBox));
  EXPECT_EQ(s.result()->color_class.space, ColorSpace::YUV);
  s.cycleSpace();
  EXPECT_EQ(s.space(), ColorSpace::RGB);
  EXPECT_EQ(s.result()->color_class.space, ColorSpace::RGB);
  s.cycleSpace();
  ASSERT_EQ(s.result()->color_class.space, ColorSpace::HSV);
  cv::Mat on_ball;
  cv::bitwise_and(s.classMask(image), ball, on_ball);
  EXPECT_GE(cv::countNonZero(on_ball), 0.95 * cv::countNonZero(ball));
  s.cycleSpace();
  EXPECT_EQ(s.space(), ColorSpace::YUV);
}

TEST(CalibrationSession, RefusesNamesAndFramesItCannotUse) {
  EXPECT_THROW(CalibrationSession("my ball", CalibrationOptions()), std::invalid_argument);
  EXPECT_THROW(CalibrationSession("", CalibrationOptions()), std::invalid_argument);
  CalibrationSession s = session();
  EXPECT_THROW(s.addFrame(cv::Mat(), "empty"), std::invalid_argument);
  EXPECT_THROW(s.addFrame(cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), "grey"), std::invalid_argument);
  EXPECT_EQ(s.frameCount(), 0);
}

TEST(CalibrationSession, BoxesGivenUpFrontAreCheckedAndMeasuredOnce) {
  cv::Mat ball;
  CalibrationSession s = session();
  CalibrationExample boxed{"boxed", scene(&ball, 9), {kBallBox}}, plain{"plain", scene(&ball, 10), {}};
  CalibrationExample outside{"outside", scene(&ball, 11), {cv::Rect(230, 170, 20, 20)}};
  EXPECT_THROW(s.addExamples({boxed, outside}), std::invalid_argument) << "a box past the 240x180 frame";
  EXPECT_EQ(s.frameCount(), 0) << "nothing kept from a refused batch";
  s.addExamples({boxed, plain});
  EXPECT_EQ(s.frameCount(), 2);
  EXPECT_EQ(s.boxCount(), 1);
  EXPECT_EQ(s.revision(), 1) << "one measurement for the batch";
  ASSERT_TRUE(s.result().has_value()) << s.lastError();
  ASSERT_TRUE(s.undo()) << "boxes given up front can be undone";
  EXPECT_FALSE(s.result().has_value());
}

TEST(CalibrationSession, ALiveFrameIsKeptOnlyWithABoxOnIt) {
  cv::Mat ball;
  const cv::Mat image = scene(&ball, 12);
  CalibrationSession s = session();
  EXPECT_EQ(s.addFrameWithBox(image, "click", cv::Rect(50, 50, 1, 1)), -1);
  EXPECT_EQ(s.frameCount(), 0) << "a click keeps no frame for the background gate";
  const int revision = s.revision();
  EXPECT_EQ(s.addFrameWithBox(image, "drag", kBallBox), 0);
  EXPECT_EQ(s.frameCount(), 1);
  EXPECT_GT(s.revision(), revision);
  EXPECT_TRUE(s.result().has_value()) << s.lastError();
}

TEST(CalibrationSession, MergingReplacesTheNamesakeAndKeepsItsVerifier) {
  ColorClass old_ball, field, new_ball;
  old_ball.name = new_ball.name = "ball";
  field.name = "field";
  old_ball.verifier_file = "ball_verifier.yml";
  old_ball.min_score = 0.7;
  new_ball.min = {{10, 20, 30}};
  const std::vector<ColorClass> merged = mergeColorClass({field, old_ball}, new_ball);
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[1].min, new_ball.min);
  EXPECT_EQ(merged[1].verifier_file, "ball_verifier.yml");
  EXPECT_DOUBLE_EQ(merged[1].min_score, 0.7);
  EXPECT_EQ(mergeColorClass({field}, new_ball).size(), 2u);
}

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(CalibrationSession, SavingWritesBothFilesOrNeither) {
  const std::string yaml = testing::TempDir() + "calibration_session.yaml";
  const std::string txt = testing::TempDir() + "calibration_session.txt";
  std::remove(yaml.c_str());
  std::remove(txt.c_str());
  ColorClass ball;
  ball.name = "ball";
  ball.min = {{50, 60, 140}};
  ball.max = {{200, 110, 200}};
  saveColorClassInto(ball, yaml, txt);
  ASSERT_EQ(loadColorClasses(yaml).size(), 1u);
  EXPECT_EQ(loadColorClasses(yaml)[0].min, ball.min);
  EXPECT_EQ(loadColorClasses(txt)[0].max, ball.max);
  ColorClass hsv = ball;
  hsv.space = ColorSpace::HSV;
  const std::string before = readAll(yaml);
  EXPECT_THROW(saveColorClassInto(hsv, yaml, txt), std::invalid_argument) << "colors.txt holds YUV only";
  EXPECT_EQ(readAll(yaml), before) << "colors.yaml was written although colors.txt could not be";
}

TEST(CalibrationView, TintsTheMaskDrawsTheBoxesAndKeepsFrameCoordinates) {
  cv::Mat ball;
  const cv::Mat image = scene(&ball, 7);
  CalibrationView view;
  view.bgr = image;
  view.mask = ball;
  view.boxes = {kBallBox};
  view.status = {"ball (YUV)"};
  view.help = "drag: box | q: quit";
  const cv::Mat picture = renderCalibrationView(view);
  ASSERT_EQ(picture.cols, image.cols);
  ASSERT_GT(picture.rows, image.rows) << "the text band goes below the frame";
  EXPECT_EQ(picture.at<cv::Vec3b>(kCentre), cv::Vec3b(255, 0, 255) * 0.6 + image.at<cv::Vec3b>(kCentre) * 0.4);
  EXPECT_EQ(picture.at<cv::Vec3b>(10, 100), image.at<cv::Vec3b>(10, 100)) << "off the mask and boxes: the frame";
  EXPECT_EQ(picture.at<cv::Vec3b>(kBallBox.y, kBallBox.x + 5), cv::Vec3b(0, 255, 0));
  view.help = std::string(400, 'x').replace(100, 1, " ").replace(200, 1, " ").replace(300, 1, " ");
  EXPECT_GT(renderCalibrationView(view).rows, picture.rows) << "a long help line wraps onto more lines";
}

}  // namespace
}  // namespace rle_vision
