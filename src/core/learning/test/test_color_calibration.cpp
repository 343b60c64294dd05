// Colour classes from examples: a box trimmed to its object, boxes that disagree dropped, the
// range kept off the image's other colours, and the rle_vision_calibrate CLI.
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rle_vision/learning/color_calibration.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/color/color_convert.h"
#include "rle_vision/io/config_error.h"
#include "rle_vision/io/yolo_labels.h"

namespace rle_vision {
namespace {

const cv::Scalar kCarpet(40, 150, 40), kBall(60, 170, 235), kRobot(20, 20, 20), kLine(120, 190, 225);

// A noisy carpet with a ball (disc) at `centre`; returns the ball's bounding box.
cv::Rect drawBall(cv::Mat* image, cv::Point centre, int radius) {
  cv::circle(*image, centre, radius, kBall, cv::FILLED, cv::LINE_8);
  return cv::Rect(centre.x - radius, centre.y - radius, 2 * radius + 1, 2 * radius + 1);
}

cv::Mat carpet() { return cv::Mat(180, 240, CV_8UC3, kCarpet); }

void addNoise(cv::Mat* image, double sigma, uint32_t seed) {
  cv::Mat noise(image->size(), CV_16SC3);
  cv::theRNG().state = seed;
  cv::randn(noise, 0, sigma);
  cv::Mat sum;
  image->convertTo(sum, CV_16SC3);
  sum += noise;
  sum.convertTo(*image, CV_8UC3);
}

Channels yuvOf(const cv::Scalar& bgr) {
  return yuvFromRgb(static_cast<int>(bgr[2]), static_cast<int>(bgr[1]), static_cast<int>(bgr[0]));
}

TEST(ColorCalibration, ADiscInItsBoxCalibratesToTheDiscNotTheCorners) {
  cv::Mat image = carpet();
  const cv::Rect box = drawBall(&image, cv::Point(120, 90), 12);
  addNoise(&image, 3, 7);
  const cv::Mat yuv = convertBgrImage(image, ColorSpace::YUV);
  CalibrationOptions options;
  const std::vector<Channels> pixels = objectPixelsInBox(yuv, box, options);
  const Channels ball = yuvOf(kBall), green = yuvOf(kCarpet);
  ASSERT_GT(pixels.size(), 300u);  // the disc holds ~450 pixels; its box 625
  for (const Channels& p : pixels) {
    for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(p[ch], ball[ch], 15) << "a corner's carpet pixel was taken";
  }
  options.exclude_background = false;
  const CalibrationResult r = calibrateColorClass({{"disc", image, {box}}}, "ball", options);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(r.stats.mean[ch], ball[ch], 1.0);
    EXPECT_NEAR(r.stats.sigma[ch], 3.0, 1.5);  // the noise, not the carpet
  }
  EXPECT_TRUE(r.color_class.contains(ball));
  EXPECT_FALSE(r.color_class.contains(green));
  EXPECT_EQ(r.color_class.name, "ball");
  EXPECT_EQ(r.color_class.min_area_px, 20u);
}

TEST(ColorCalibration, AnOccluderAtTheSideIsNotTheObject) {
  cv::Mat image = carpet();
  const cv::Rect box = drawBall(&image, cv::Point(120, 90), 14);
  cv::rectangle(image, cv::Rect(box.x - 20, box.y, 26, box.height), kRobot, cv::FILLED);  // the robot holding it
  addNoise(&image, 3, 8);
  const std::vector<Channels> pixels = objectPixelsInBox(convertBgrImage(image, ColorSpace::YUV), box, CalibrationOptions());
  ASSERT_GT(pixels.size(), 200u);
  const Channels ball = yuvOf(kBall);
  for (const Channels& p : pixels) ASSERT_NEAR(p[0], ball[0], 15);
}

TEST(ColorCalibration, ABoxThatDisagreesWithTheOthersIsDropped) {
  std::vector<CalibrationExample> examples;
  for (int i = 0; i < 4; ++i) {
    cv::Mat image = carpet();
    const cv::Rect box = drawBall(&image, cv::Point(60 + 30 * i, 90), 8 + 2 * i);
    addNoise(&image, 3, 20 + i);
    examples.push_back({"ball" + std::to_string(i), image, {box}});
  }
  cv::Mat wrong = carpet();
  cv::rectangle(wrong, cv::Rect(100, 70, 30, 30), cv::Scalar(200, 60, 30), cv::FILLED);  // a box on a blue thing
  examples.push_back({"wrong", wrong, {cv::Rect(100, 70, 30, 30)}});
  CalibrationOptions options;
  options.exclude_background = false;
  const CalibrationResult r = calibrateColorClass(examples, "ball", options);
  EXPECT_EQ(r.boxes_used, 4);
  EXPECT_EQ(r.boxes_dropped, 1);
  EXPECT_TRUE(r.color_class.contains(yuvOf(kBall)));
  EXPECT_FALSE(r.color_class.contains(yuvOf(cv::Scalar(200, 60, 30))));
}

TEST(ColorCalibration, TheBackgroundGateKeepsNearbyColoursOut) {
  // Balls under changing light (brightness 0.75..1.15) beside pale yellow lines, whose colour the
  // statistics' range (mean +- 3 sigma over all examples) reaches.
  std::vector<CalibrationExample> examples;
  for (int i = 0; i < 6; ++i) {
    cv::Mat image = carpet();
    cv::line(image, cv::Point(0, 20 + 20 * i), cv::Point(239, 40 + 10 * i), kLine, 5);
    const cv::Rect box = drawBall(&image, cv::Point(40 + 30 * i, 120), 9);
    cv::Mat ball_area = image(box);
    ball_area *= 0.75 + 0.08 * i;
    addNoise(&image, 4, 30 + i);
    examples.push_back({"frame" + std::to_string(i), image, {box}});
  }
  CalibrationOptions plain;
  plain.exclude_background = false;
  const CalibrationResult wide = calibrateColorClass(examples, "ball", plain);
  const CalibrationResult gated = calibrateColorClass(examples, "ball", CalibrationOptions());
  EXPECT_GT(wide.other_pixels_per_image, 100) << "the test needs a range that reaches the lines";
  EXPECT_LT(gated.other_pixels_per_image, 0.05 * wide.other_pixels_per_image);
  EXPECT_GT(gated.object_recall, 0.9);
  EXPECT_FALSE(gated.color_class.contains(yuvOf(kLine)));
  EXPECT_FALSE(gated.color_class.contains(yuvOf(kCarpet)));
}

TEST(ColorCalibration, TwoBoxesThatDisagreeKeepOneNotNone) {
  cv::Mat a = carpet(), b = carpet();
  const cv::Rect box_a = drawBall(&a, cv::Point(60, 90), 10);
  cv::rectangle(b, box_a, cv::Scalar(200, 60, 30), cv::FILLED);
  CalibrationOptions options;
  options.exclude_background = false;
  const CalibrationResult r = calibrateColorClass({{"a", a, {box_a}}, {"b", b, {box_a}}}, "ball", options);
  EXPECT_EQ(r.boxes_used, 1);
  EXPECT_EQ(r.boxes_dropped, 1);
  for (int ch = 0; ch < 3; ++ch) EXPECT_FALSE(std::isnan(r.stats.mean[ch]));
}

TEST(YoloLabels, ClassFilterClampingAndErrors) {
  const std::string dir = testing::TempDir();
  const std::string path = dir + "/rle_vision_labels.txt";
  std::ofstream(path) << "0 0.5 0.5 0.2 0.1\n1 0.1 0.1 0.1 0.1\n\n0 0.98 0.5 0.1 0.1\n0 0.3 0.3 0.0001 0.0001\n";
  const std::vector<cv::Rect> boxes = readYoloBoxes(path, 0, cv::Size(200, 100));
  ASSERT_EQ(boxes.size(), 3u);
  EXPECT_EQ(boxes[0], cv::Rect(80, 45, 40, 10));
  EXPECT_EQ(boxes[1], cv::Rect(186, 45, 14, 10));  // clamped at the right border
  EXPECT_EQ(boxes[2], cv::Rect(60, 30, 1, 1));     // at least one pixel
  EXPECT_TRUE(readYoloBoxes(dir + "/rle_vision_no_such_labels.txt", 0, cv::Size(200, 100)).empty());
  EXPECT_EQ(yoloLabelPath("/a.b/frame.jpg"), "/a.b/frame.txt");
  EXPECT_EQ(yoloLabelPath("/a.b/frame"), "/a.b/frame.txt");
  std::ofstream(path) << "0 0.5 0.5 0.2 0.1 0.7 0.7\n";  // a polygon label
  EXPECT_THROW(readYoloBoxes(path, 0, cv::Size(200, 100)), ConfigError);
  std::ofstream(path) << "0 0.5 0.5 0 0.1\n";
  EXPECT_THROW(readYoloBoxes(path, 0, cv::Size(200, 100)), ConfigError);
  std::ofstream(path) << "0 1.5 0.5 0.1 0.1\n";
  EXPECT_THROW(readYoloBoxes(path, 0, cv::Size(200, 100)), ConfigError);
}

TEST(ColorCalibration, BadExamplesGetAClearError) {
  const cv::Mat image = carpet();
  auto message = [&](const CalibrationExample& e) {
    try {
      calibrateColorClass({e}, "ball");
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({"a.png", image, {cv::Rect(230, 10, 20, 20)}}),
            "a.png: box 230,10,250,30 lies outside the 240x180 image");
  EXPECT_EQ(message({"a.png", image, {cv::Rect(10, 10, 0, 5)}}), "a.png: box 10,10,10,15 is empty");
  EXPECT_EQ(message({"b.png", cv::Mat(), {cv::Rect(0, 0, 5, 5)}}), "b.png: empty or unreadable image");
  EXPECT_NE(message({"a.png", image, {}}).find("no box holds object pixels"), std::string::npos);
}

TEST(ColorCalibration, CmvisionTextReadsBackAndRefusesOtherSpaces) {
  ColorClass c;
  c.name = "ball";
  c.min = {{150, 72, 116}};
  c.max = {{255, 119, 167}};
  c.display_rgb = {{230, 200, 120}};
  const std::vector<ColorClass> back = parseCmvisionColors(cmvisionColorsText({c}), "calibrated");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].name, "ball");
  EXPECT_EQ(back[0].min, c.min);
  EXPECT_EQ(back[0].max, c.max);
  EXPECT_EQ(cmvisionColorsText({c}).find('#'), std::string::npos) << "CMVision ends a section at a comment";
  c.space = ColorSpace::HSV;
  EXPECT_THROW(cmvisionColorsText({c}), std::invalid_argument);
}

std::string run(const std::string& command, int* status) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    *status = -1;
    return out;
  }
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) out.append(buffer, n);
  *status = WEXITSTATUS(pclose(pipe));
  return out;
}

TEST(CalibrateCli, WritesTheClassFromBoxesOrYoloLabelsAndRefusesBadInput) {
  const std::string dir = testing::TempDir() + "/rle_vision_calibrate";
  ASSERT_EQ(std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str()), 0);
  cv::Mat image = carpet();
  const cv::Rect box = drawBall(&image, cv::Point(120, 90), 12);
  addNoise(&image, 3, 11);
  ASSERT_TRUE(cv::imwrite(dir + "/f.png", image));
  const std::string tool = RLE_VISION_CALIBRATE;
  int status = 0;
  const std::string box_arg = " --box " + std::to_string(box.x) + "," + std::to_string(box.y) + "," +
                              std::to_string(box.br().x) + "," + std::to_string(box.br().y);
  run(tool + " --name ball " + dir + "/f.png" + box_arg + " --output " + dir + "/colors.yaml --cmvision " + dir +
          "/colors.txt 2>/dev/null",
      &status);
  ASSERT_EQ(status, 0);
  const std::vector<ColorClass> from_box = loadColorClasses(dir + "/colors.yaml");
  ASSERT_EQ(from_box.size(), 1u);
  EXPECT_TRUE(from_box[0].contains(yuvOf(kBall)));
  EXPECT_FALSE(from_box[0].contains(yuvOf(kCarpet)));
  EXPECT_EQ(loadColorClasses(dir + "/colors.txt")[0].min, from_box[0].min);
  const CalibrationResult core = calibrateColorClass({{"f", cv::imread(dir + "/f.png"), {box}}}, "ball");
  EXPECT_EQ(from_box[0].min, core.color_class.min);
  EXPECT_EQ(from_box[0].max, core.color_class.max);
  // Calibrating a class that has a verifier keeps it, its path as written (relative to the file).
  std::ofstream(dir + "/verified.yaml") << "classes:\n  - name: ball\n    min: [0, 0, 0]\n    max: [9, 9, 9]\n"
                                           "    verifier_file: models/ball.yml\n    min_score: 0.7\n";
  run(tool + " --name ball " + dir + "/f.png" + box_arg + " --output " + dir + "/verified.yaml 2>/dev/null", &status);
  ASSERT_EQ(status, 0);
  const std::vector<ColorClass> verified = loadColorClasses(dir + "/verified.yaml");
  ASSERT_EQ(verified.size(), 1u);
  EXPECT_EQ(verified[0].min, core.color_class.min);
  EXPECT_EQ(verified[0].verifier_file, "models/ball.yml");
  EXPECT_DOUBLE_EQ(verified[0].min_score, 0.7);
  // The same box as a YOLO label (class 3), and another class's label, on a blue object, that
  // must be ignored (taken, it would be dropped and counted, or widen the range).
  cv::rectangle(image, cv::Rect(12, 9, 12, 9), cv::Scalar(200, 60, 30), cv::FILLED);
  ASSERT_TRUE(cv::imwrite(dir + "/f.png", image));
  const CalibrationResult expected = calibrateColorClass({{"f", cv::imread(dir + "/f.png"), {box}}}, "ball");
  std::ofstream(dir + "/f.txt") << "1 0.075 0.075 0.05 0.05\n3 " << (box.x + box.width / 2.0) / 240 << " "
                                << (box.y + box.height / 2.0) / 180 << " " << box.width / 240.0 << " "
                                << box.height / 180.0 << "\n";
  const std::string yaml = run(tool + " --name ball --label-class 3 " + dir + " 2>" + dir + "/summary", &status);
  EXPECT_EQ(status, 0);
  const ColorClass from_labels = parseColorClassesYaml(yaml.substr(0, yaml.find("[Colors]")), "stdout")[0];
  EXPECT_EQ(from_labels.min, expected.color_class.min);
  EXPECT_EQ(from_labels.max, expected.color_class.max);
  std::ifstream summary(dir + "/summary");
  const std::string summary_text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(summary_text.find("1 boxes used, 0 dropped"), std::string::npos) << summary_text;
  // Bad input: exit 2 and a message naming the problem.
  run(tool + " --name ball " + dir + "/f.png --box 230,10,250,30 2>" + dir + "/err", &status);
  EXPECT_EQ(status, 2);
  std::ifstream err(dir + "/err");
  const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("lies outside the 240x180 image"), std::string::npos) << text;
  run(tool + " --name ball /nonexistent.png --box 1,1,5,5 2>/dev/null", &status);
  EXPECT_EQ(status, 2);
  run(tool + " --name ball " + dir + "/f.png --box 5,5,5,9 2>/dev/null", &status);
  EXPECT_EQ(status, 2);
  run(tool + " --name ball " + dir + "/f.png --box 1,2,3 2>/dev/null", &status);
  EXPECT_EQ(status, 2);
  run(tool + " --name 'ball: x' " + dir + "/f.png" + box_arg + " 2>/dev/null", &status);
  EXPECT_EQ(status, 2);
  run(tool + " --name ball --min-area 0 " + dir + "/f.png" + box_arg + " 2>/dev/null", &status);
  EXPECT_EQ(status, 2);
}

}  // namespace
}  // namespace rle_vision
