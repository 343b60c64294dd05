// Builds against rle_vision's public headers (std::optional in latest_mailbox.h needs C++17)
// and its core library, and finds the one red square of a synthetic frame with the package's
// colours file (argv[1]: $(rospack find rle_vision)/config/colors.yaml): exit status 0 when it
// does.
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "rle_vision/common/latest_mailbox.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/tracking/color_tracker.h"

int main(int argc, char** argv) {
  using namespace rle_vision;
  if (argc != 2) {
    std::fprintf(stderr, "usage: downstream_blobs COLORS_FILE\n");
    return 2;
  }
  const std::vector<ColorClass> classes = loadColorClasses(argv[1]);
  cv::Mat frame(120, 160, CV_8UC3, cv::Scalar(60, 120, 70));
  cv::rectangle(frame, cv::Rect(40, 30, 20, 20), cv::Scalar(30, 30, 220), cv::FILLED);  // red, BGR
  ColorTracker tracker;
  std::vector<TrackedBlob> blobs;
  tracker.process(frame, PixelFormat::BGR8, ColorTable(classes), 0.0, &blobs);
  LatestMailbox<size_t> mailbox;
  mailbox.put(blobs.size());
  std::printf("%zu blob(s)\n", blobs.size());
  return blobs.size() == 1 && blobs[0].region.area == 400 ? 0 : 1;
}
