// The GroundProjector nodelet as a plain node.
#include "nodelet_runner.h"

int main(int argc, char** argv) {
  return rle_vision::runNodelet(argc, argv, "ground_projector", "rle_vision/GroundProjector");
}
