// For the verifier rostest: writes FRAMES synthetic labelled frames (a shaded ball among a bar
// and a patch of the same yellow, src/core/testing/verifier_scenes.h) to FOLDER as PNG images
// with YOLO labels (class 0: the ball), drawn from SEED.
//
//   verifier_scene_frames FOLDER FRAMES SEED
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "testing/verifier_scenes.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: verifier_scene_frames FOLDER FRAMES SEED\n");
    return 2;
  }
  const std::string folder = argv[1];
  const int frames = std::atoi(argv[2]);
  cv::RNG rng(std::strtoull(argv[3], nullptr, 10));
  for (int i = 0; i < frames; ++i) {
    const rle_vision::test::VerifierFrame f = rle_vision::test::drawVerifierFrame(rng);
    const std::string name = folder + "/frame_" + std::to_string(i);
    if (!cv::imwrite(name + ".png", f.bgr)) {
      std::fprintf(stderr, "verifier_scene_frames: cannot write %s.png\n", name.c_str());
      return 1;
    }
    std::ofstream label(name + ".txt");
    for (const cv::Rect& b : f.balls) {
      label << "0 " << (b.x + 0.5 * b.width) / f.bgr.cols << " " << (b.y + 0.5 * b.height) / f.bgr.rows << " "
            << static_cast<double>(b.width) / f.bgr.cols << " " << static_cast<double>(b.height) / f.bgr.rows << "\n";
    }
  }
  return 0;
}
