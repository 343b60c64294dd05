// rle_vision_detect on image files: JSON per image with blobs, lines and the horizon; an
// unreadable file gives an error entry and a non-zero exit status, never a crash.
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "rle_vision/sim/scene_file.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

// Runs a command; returns its stdout and sets the exit status.
std::string run(const std::string& command, int* status) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) out.append(buffer, n);
  *status = WEXITSTATUS(pclose(pipe));
  return out;
}

TEST(DetectCli, JsonPerImageAndErrorsForUnreadableFiles) {
  const std::string dir = testing::TempDir();
  const SimFrame frame = SceneSimulator(loadSceneConfig(test::sourcePath("config/scene_default.yaml"))).render(0, 0);
  const std::string good = dir + "/rle_vision_frame.png", bad = dir + "/rle_vision_not_an_image.png";
  ASSERT_TRUE(cv::imwrite(good, frame.image));
  std::ofstream(bad) << "this is not a PNG";
  int status = 0;
  const std::string out = run(std::string(RLE_VISION_DETECT) + " --annotate " + dir + " " + good + " " + bad +
                                  " /nonexistent.png",
                              &status);
  EXPECT_EQ(status, 1) << "unreadable files must give a non-zero exit";
  std::istringstream lines(out);
  std::string first, second, third;
  std::getline(lines, first);
  std::getline(lines, second);
  std::getline(lines, third);
  EXPECT_NE(first.find("\"file\":\"" + good + "\",\"width\":640,\"height\":480,\"blobs\":[{"), std::string::npos) << first;
  EXPECT_NE(first.find("\"color\":\"red\""), std::string::npos);
  EXPECT_NE(first.find("\"lines\":[{\"theta\":"), std::string::npos);
  EXPECT_NE(first.find("\"horizon\":{\"found\":true,\"confidence\":0."), std::string::npos) << first;
  EXPECT_NE(second.find("\"error\":"), std::string::npos) << second;
  EXPECT_NE(third.find("\"file\":\"/nonexistent.png\",\"error\":"), std::string::npos) << third;
  EXPECT_FALSE(cv::imread(dir + "/rle_vision_frame.png").empty());  // the annotated overlay
  // A folder that does not exist yet is made; one that cannot be (under a file) exits 2.
  const std::string made = dir + "/rle_vision_annotated/new";
  run(std::string(RLE_VISION_DETECT) + " --annotate " + made + " " + good + " > /dev/null", &status);
  EXPECT_EQ(status, 0);
  EXPECT_FALSE(cv::imread(made + "/rle_vision_frame.png").empty());
  run(std::string(RLE_VISION_DETECT) + " --annotate " + bad + "/sub " + good + " > /dev/null 2>&1", &status);
  EXPECT_EQ(status, 2);
  // Bad options fail at once with a usage message.
  run(std::string(RLE_VISION_DETECT) + " --colors /nonexistent.yaml " + good + " 2>/dev/null", &status);
  EXPECT_EQ(status, 2);
}

int countOf(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// --sequence: frames of the drifting-light scene (30 s, 2 frames a second) are one stream;
// ranges learned on a frame are used on the next, so the boxes stay found as the light dims,
// and each line says which ranges were in use.
TEST(DetectCli, SequenceCarriesLearnedRangesFromFrameToFrame) {
  const std::string dir = testing::TempDir() + "/rle_vision_sequence";
  ASSERT_EQ(std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str()), 0);
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_drift.yaml")));
  std::string frames;
  for (int i = 0; i <= 60; ++i) {
    char name[64];
    std::snprintf(name, sizeof(name), "/frame_%03d.png", i);
    ASSERT_TRUE(cv::imwrite(dir + name, simulator.render(i * 15, i * 0.5).image));
    frames += " " + dir + name;
  }
  std::ofstream(dir + "/fixed.yaml") << "learning: false\n";
  int status = 0;
  const std::string learned = run(std::string(RLE_VISION_DETECT) + " --sequence --fps 2" + frames, &status);
  ASSERT_EQ(status, 0);
  const std::string fixed =
      run(std::string(RLE_VISION_DETECT) + " --sequence --fps 2 --params " + dir + "/fixed.yaml" + frames, &status);
  ASSERT_EQ(status, 0);
  auto line = [](const std::string& text, int index) {
    std::istringstream lines(text);
    std::string l;
    for (int i = 0; i <= index; ++i) std::getline(lines, l);
    return l;
  };
  const std::string first = line(learned, 0), last_learned = line(learned, 60), last_fixed = line(fixed, 60);
  EXPECT_EQ(countOf(first, "\"source\":\"config\""), 4) << first;
  EXPECT_GE(countOf(last_learned, "\"source\":\"learned\""), 3) << last_learned;
  EXPECT_EQ(countOf(last_fixed, "\"source\":\"learned\""), 0);
  const int blobs_first = countOf(first, "\"color\":"), blobs_learned = countOf(last_learned, "\"color\":"),
            blobs_fixed = countOf(last_fixed, "\"color\":");
  std::printf("[ sequence ] blobs on the first frame %d; on the last: learning %d, fixed ranges %d\n", blobs_first,
              blobs_learned, blobs_fixed);
  EXPECT_GE(blobs_learned, blobs_first - 2);
  EXPECT_LT(blobs_fixed, blobs_first / 2);
  // Track ids carry over from frame to frame (not reset per image): three frames at 30 Hz.
  auto ids = [](const std::string& json) {
    const std::regex id("\"id\":([0-9]+),");
    std::set<int> out;
    for (std::sregex_iterator m(json.begin(), json.end(), id), end; m != end; ++m) out.insert(std::stoi((*m)[1].str()));
    return out;
  };
  // The scene (ids 1..10), then blank frames until those tracks are forgotten, then three
  // frames of the scene: a tracker kept from image to image gives them new ids (11..20), the
  // same on all three; a tracker per image would give 1..10 again.
  std::string video = " " + dir + "/first.png";
  ASSERT_TRUE(cv::imwrite(dir + "/first.png", simulator.render(0, 0.0).image));
  ASSERT_TRUE(cv::imwrite(dir + "/blank.png", cv::Mat(480, 640, CV_8UC3, cv::Scalar(128, 128, 128))));
  for (int i = 0; i < 6; ++i) video += " " + dir + "/blank.png";
  for (int i = 0; i < 3; ++i) {
    const std::string name = dir + "/video_" + std::to_string(i) + ".png";
    ASSERT_TRUE(cv::imwrite(name, simulator.render(i, i / 30.0).image));
    video += " " + name;
  }
  const std::string tracked = run(std::string(RLE_VISION_DETECT) + " --sequence" + video, &status);
  ASSERT_EQ(status, 0);
  EXPECT_EQ(ids(line(tracked, 0)).size(), 10u) << tracked;
  const std::set<int> later_ids = ids(line(tracked, 7));
  EXPECT_EQ(later_ids.size(), 10u) << tracked;
  EXPECT_GT(*later_ids.begin(), 10) << "a new tracker per image: " << tracked;
  EXPECT_EQ(ids(line(tracked, 8)), later_ids);
  EXPECT_EQ(ids(line(tracked, 9)), later_ids);
  run(std::string(RLE_VISION_DETECT) + " --fps 10 " + dir + "/first.png 2>/dev/null", &status);
  EXPECT_EQ(status, 2) << "--fps without --sequence";
  EXPECT_EQ(line(run(std::string(RLE_VISION_DETECT) + " " + dir + "/frame_000.png", &status), 0).find("\"ranges\""),
            std::string::npos);
}

// The field stage reads its parameters from --params too, and --sequence publishes the floor's
// colour as class "field" (learning_field_class), as the Landmark node does.
TEST(DetectCli, FieldParametersAndTheFieldClass) {
  const std::string dir = testing::TempDir() + "/rle_vision_field";
  ASSERT_EQ(std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str()), 0);
  const SceneSimulator simulator(loadSceneConfig(test::sourcePath("config/scene_field.yaml")));
  std::string frames;
  for (int i = 0; i < 4; ++i) {
    const std::string name = dir + "/hall_" + std::to_string(i) + ".png";
    ASSERT_TRUE(cv::imwrite(name, simulator.render(i, i / 30.0).image));
    frames += " " + name;
  }
  std::ofstream(dir + "/field_class.yaml") << "learning_field_class: true\n";
  std::ofstream(dir + "/no_floor.yaml") << "field_min_share: 1.0\n";  // the floor must fill the whole band
  int status = 0;
  const std::string plain = run(std::string(RLE_VISION_DETECT) + " --sequence" + frames, &status);
  ASSERT_EQ(status, 0);
  const std::string with_field =
      run(std::string(RLE_VISION_DETECT) + " --sequence --params " + dir + "/field_class.yaml" + frames, &status);
  ASSERT_EQ(status, 0);
  EXPECT_EQ(countOf(plain, "\"color\":\"field\""), 0);
  EXPECT_GE(countOf(with_field, "\"color\":\"field\""), 2) << with_field;  // from the second frame on
  const std::string image = dir + "/hall_0.png";
  EXPECT_NE(run(std::string(RLE_VISION_DETECT) + " " + image, &status).find("\"field_boundary\":{\"found\":true"),
            std::string::npos);
  EXPECT_NE(run(std::string(RLE_VISION_DETECT) + " --params " + dir + "/no_floor.yaml " + image, &status)
                .find("\"field_boundary\":{\"found\":false"),
            std::string::npos);
}

}  // namespace
}  // namespace rle_vision
