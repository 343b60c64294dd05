// The EdgeDetector nodelet as a plain node.
#include "nodelet_runner.h"

int main(int argc, char** argv) {
  return rle_vision::runNodelet(argc, argv, "edge_detector", "rle_vision/EdgeDetector");
}
