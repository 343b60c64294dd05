// rle_vision_detect on image files: JSON per image with blobs, lines and the horizon; an
// unreadable file gives an error entry and a non-zero exit status, never a crash.
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "rle_vision/scene_file.h"
#include "test_helpers.h"

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
  // Bad options fail at once with a usage message.
  run(std::string(RLE_VISION_DETECT) + " --colors /nonexistent.yaml " + good + " 2>/dev/null", &status);
  EXPECT_EQ(status, 2);
}

}  // namespace
}  // namespace rle_vision
