// Our blobs and OpenCV's (cvtColor + inRange + connectedComponentsWithStats per class) agree on
// the benchmark frame: the speed comparison in `make bench` compares equal work.
#include <algorithm>

#include <gtest/gtest.h>

#include "eval/benchmark_frame.h"
#include "eval/opencv_pipeline.h"
#include "rle_vision/segment/segmenter.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

TEST(OpenCvAgreement, SameBlobsOnTheBenchmarkFrame) {
  const SimFrame frame = benchmarkFrame(RLE_VISION_SOURCE_DIR);
  const std::vector<ColorClass> classes = benchmarkClasses(RLE_VISION_SOURCE_DIR);
  ASSERT_EQ(classes.size(), 4u);
  // inRange masks are independent while our classes have a priority: the comparison is only
  // the same job when no pixel can belong to two classes.
  for (size_t a = 0; a < classes.size(); ++a) {
    for (size_t b = a + 1; b < classes.size(); ++b) {
      bool overlap = true;
      for (int ch = 0; ch < 3; ++ch) {
        overlap = overlap && classes[a].min[ch] <= classes[b].max[ch] && classes[b].min[ch] <= classes[a].max[ch];
      }
      EXPECT_FALSE(overlap) << classes[a].name << " and " << classes[b].name << " overlap";
    }
  }
  const ColorTable table(classes);
  Segmenter segmenter;
  std::vector<Region> ours;
  segmenter.segment(frame.image, PixelFormat::BGR8, table, &ours);
  OpenCvPipeline opencv(classes);
  std::vector<OpenCvBlob> theirs;
  opencv.run(frame.image, &theirs);
  ASSERT_GE(ours.size(), 8u) << "the benchmark frame should show about ten objects";
  ASSERT_EQ(ours.size(), theirs.size());
  for (const OpenCvBlob& blob : theirs) {
    const auto match = std::find_if(ours.begin(), ours.end(), [&](const Region& r) {
      return r.label == blob.label && std::hypot(r.cx - blob.cx, r.cy - blob.cy) <= 0.5;
    });
    ASSERT_NE(match, ours.end()) << "no blob of ours near OpenCV's at " << blob.cx << "," << blob.cy;
    EXPECT_EQ(static_cast<int>(match->area), blob.area);
    EXPECT_EQ(match->left, blob.bbox.x);
    EXPECT_EQ(match->top, blob.bbox.y);
    EXPECT_EQ(match->right, blob.bbox.x + blob.bbox.width - 1);
    EXPECT_EQ(match->bottom, blob.bbox.y + blob.bbox.height - 1);
  }
}

}  // namespace
}  // namespace rle_vision
