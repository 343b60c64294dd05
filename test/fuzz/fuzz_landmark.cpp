// libFuzzer target: the edge/Hough core on arbitrary sizes and bytes. The first bytes choose
// the size (1..160 x 1..120) and whether the bytes are a BGR image (Sobel first) or an edge
// image; the rest are pixels. Lines must be finite and the horizon's confidence in [0, 1].
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include <opencv2/core.hpp>

#include "rle_vision/learning/color_learning.h"
#include "rle_vision/io/config_error.h"
#include "rle_vision/landmark/landmark_detector.h"

using namespace rle_vision;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  const int width = 1 + data[0] % 160, height = 1 + data[1] % 120;
  const bool colour = data[2] % 2;
  data += 3;
  size -= 3;
  cv::Mat image(height, width, colour ? CV_8UC3 : CV_8UC1, cv::Scalar::all(0));
  const size_t bytes = std::min(size, image.total() * image.elemSize());
  std::copy(data, data + bytes, image.data);
  LandmarkDetector detector;
  LandmarkResult result;
  if (colour) {
    detector.detectInImage(image, LandmarkOptions(), &result);
  } else {
    detector.detectInEdges(image, LandmarkOptions(), &result);
  }
  for (const DetectedLine& l : result.lines) {
    if (!std::isfinite(l.x1) || !std::isfinite(l.y1) || !std::isfinite(l.x2) || !std::isfinite(l.y2)) abort();
  }
  if (result.horizon.found && !(result.horizon.confidence >= 0 && result.horizon.confidence <= 1)) abort();
  if (colour) {  // colour learning on what the landmarks found
    static const std::vector<ColorClass> classes = {[] {
      ColorClass c;
      c.name = "red";
      c.min = {{30, 85, 184}};
      c.max = {{150, 128, 255}};
      return c;
    }()};
    ColorLearner learner(classes, LearningOptions());
    learner.update(image, result, detector.edgeObjects(), 0.0);
  }
  return 0;
}
