// rle_vision_train on folders of synthetic labelled frames (a shaded ball among same-coloured
// shapes): it writes a verifier that loads, prints the held-out figures of each folder (over
// 90% of the ball candidates kept, over 90% of those kept on a ball) and that rle_vision_detect
// --verifier uses on unseen frames; both refuse bad input with a one-line reason and exit status 2.
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "rle_vision/verify/blob_verifier.h"
#include "rle_vision/verify/verifier_training.h"
#include "testing/test_helpers.h"
#include "testing/verifier_scenes.h"

namespace rle_vision {
namespace {

std::string run(const std::string& command, int* status) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) out.append(buffer, n);
  *status = WEXITSTATUS(pclose(pipe));
  return out;
}

// `frames` labelled frames in `folder` (YOLO: class 0, the ball; `labels` false: none).
void writeFolder(const std::string& folder, int frames, uint64_t seed, bool labels = true) {
  ASSERT_EQ(std::system(("rm -rf " + folder + " && mkdir -p " + folder).c_str()), 0);
  ASSERT_EQ(test::writeVerifierFolder(folder, frames, seed, labels), "");
}

TEST(TrainCli, WritesAVerifierThatLoadsAndReportsHeldOutFolders) {
  const std::string dir = testing::TempDir() + "/rle_vision_train";
  writeFolder(dir + "/a", 30, 1);
  writeFolder(dir + "/b", 30, 2);
  int status = 0;
  // One light in both folders: the covering range is the ball's own, and the same-coloured
  // shapes become candidates only with the range widened.
  const std::string out = run(std::string(RLE_VISION_TRAIN) + " --class ball --label-class 0 --widen 16 --output " +
                                  dir + "/ball_verifier.yml " + dir + "/a " + dir + "/b",
                              &status);
  ASSERT_EQ(status, 0) << out;
  // Each folder held out: the candidates on a ball kept, the others dropped (recall and
  // precision of the candidates over 90%).
  const std::regex held("held out ([ab]) .*recall +([0-9.]+)%, precision +([0-9.]+)%");
  int folders = 0;
  for (std::sregex_iterator m(out.begin(), out.end(), held), end; m != end; ++m, ++folders) {
    EXPECT_GE(std::stod((*m)[2].str()), 90.0) << (*m)[0];
    EXPECT_GE(std::stod((*m)[3].str()), 90.0) << (*m)[0];
  }
  EXPECT_EQ(folders, 2) << out;
  const BlobVerifier verifier = BlobVerifier::load(dir + "/ball_verifier.yml");
  EXPECT_TRUE(verifier.trained());
  EXPECT_EQ(verifier.candidateRange().name, "ball");
  std::printf("%s", out.c_str());
  // How it was made is noted at the top of the file.
  std::ifstream file(dir + "/ball_verifier.yml");
  std::string head((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(head.find("# Made by rle_vision_train --class ball --label-class 0 --widen 16 from the folders a b (60 frames)"),
            std::string::npos) << head.substr(0, 400);
  EXPECT_NE(head.find("# held out a "), std::string::npos) << head.substr(0, 800);
  EXPECT_NE(head.find("# 2 models, one per folder, each trained without it"), std::string::npos) << head.substr(0, 800);
  EXPECT_EQ(verifier.modelCount(), 2);
  // The floor guard's scale, chosen by the folders held out in turn, is kept in the file.
  char chosen_line[64];
  std::snprintf(chosen_line, sizeof(chosen_line), "# floor guard scale %.1f: held-out mean F1", verifier.floorGuardScale());
  EXPECT_NE(head.find(chosen_line), std::string::npos) << head.substr(0, 800);
  const std::vector<double>& tried = floorGuardScalesTried();
  EXPECT_NE(std::find(tried.begin(), tried.end(), verifier.floorGuardScale()), tried.end());

  // rle_vision_detect --verifier on frames neither folder had: the ball is found with its score
  // (its class and range come from the verifier file), the same-coloured shapes are not.
  cv::RNG rng(77);
  const std::regex blob("\\{[^{}]*\"color\":\"ball\"[^{}]*\"cx\":([-0-9.e]+),\"cy\":([-0-9.e]+)[^{}]*\"score\":([0-9.e-]+)\\}");
  int balls_found = 0, others_found = 0;
  for (int i = 0; i < 10; ++i) {
    const test::VerifierFrame f = test::drawVerifierFrame(rng);
    ASSERT_TRUE(cv::imwrite(dir + "/unseen.png", f.bgr));
    const std::string json = run(std::string(RLE_VISION_DETECT) + " --colors " + test::sourcePath("config/colors.yaml") +
                                     " --verifier " + dir + "/ball_verifier.yml --min-score 0.5 " + dir + "/unseen.png",
                                 &status);
    ASSERT_EQ(status, 0) << json;
    for (std::sregex_iterator m(json.begin(), json.end(), blob), end; m != end; ++m) {
      EXPECT_GE(std::stod((*m)[3].str()), 0.5) << (*m)[0];
      const cv::Point2d c(std::stod((*m)[1].str()), std::stod((*m)[2].str()));
      (f.balls[0].contains(cv::Point(static_cast<int>(c.x), static_cast<int>(c.y))) ? balls_found : others_found) += 1;
    }
  }
  EXPECT_GE(balls_found, 9);
  EXPECT_LE(others_found, 1);
}

TEST(TrainCli, BadInputGetsOneLineAndStatusTwo) {
  const std::string dir = testing::TempDir() + "/rle_vision_train_bad";
  writeFolder(dir + "/unlabelled", 3, 3, false);
  ASSERT_EQ(std::system(("mkdir -p " + dir + "/empty").c_str()), 0);
  const std::string train = std::string(RLE_VISION_TRAIN) + " --class ball --label-class 0 --output " + dir + "/v.yml ";
  int status = 0;
  std::string out = run(train + dir + "/unlabelled", &status);
  EXPECT_EQ(status, 2);
  EXPECT_NE(out.find("rle_vision_train: no box of label class 0"), std::string::npos) << out;
  out = run(train + dir + "/empty", &status);
  EXPECT_EQ(status, 2);
  EXPECT_NE(out.find("no .jpg, .jpeg or .png images"), std::string::npos) << out;
  out = run(std::string(RLE_VISION_TRAIN) + " --class ball " + dir + "/unlabelled", &status);
  EXPECT_EQ(status, 2);
  EXPECT_NE(out.find("usage: rle_vision_train"), std::string::npos) << out;
  out = run(std::string(RLE_VISION_TRAIN) + " --class ball --label-class x --output v.yml " + dir, &status);
  EXPECT_EQ(status, 2);
  // rle_vision_detect: a missing verifier, --min-score without one or out of 0..1.
  const std::string image = dir + "/unlabelled/frame_0.png";
  out = run(std::string(RLE_VISION_DETECT) + " --verifier " + dir + "/none.yml " + image, &status);
  EXPECT_EQ(status, 2);
  EXPECT_NE(out.find("rle_vision_detect: " + dir + "/none.yml: cannot read the verifier file"), std::string::npos) << out;
  out = run(std::string(RLE_VISION_DETECT) + " --min-score 0.5 " + image, &status);
  EXPECT_EQ(status, 2);
  EXPECT_NE(out.find("--min-score needs --verifier"), std::string::npos) << out;
  out = run(std::string(RLE_VISION_DETECT) + " --verifier v.yml --min-score 2 " + image, &status);
  EXPECT_EQ(status, 2);
  EXPECT_NE(out.find("--min-score needs a score from 0 to 1"), std::string::npos) << out;
}

}  // namespace
}  // namespace rle_vision
