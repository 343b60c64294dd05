// For the verifier rostest: writes FRAMES synthetic labelled frames (a shaded ball among a bar
// and a patch of the same yellow, src/core/testing/verifier_scenes.h) to FOLDER as PNG images
// with YOLO labels (class 0: the ball), drawn from SEED.
//
//   verifier_scene_frames FOLDER FRAMES SEED
#include <cstdio>
#include <cstdlib>
#include <string>

#include "testing/verifier_scenes.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: verifier_scene_frames FOLDER FRAMES SEED\n");
    return 2;
  }
  const std::string problem =
      rle_vision::test::writeVerifierFolder(argv[1], std::atoi(argv[2]), std::strtoull(argv[3], nullptr, 10));
  if (!problem.empty()) {
    std::fprintf(stderr, "verifier_scene_frames: %s\n", problem.c_str());
    return 1;
  }
  return 0;
}
