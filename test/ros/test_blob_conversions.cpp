// The tracker's blobs in message form: our own Blob keeps inclusive edges; the cmvision-shaped
// message uses CMVision's convention (right one past the last column, bottom the last row).
#include <cmath>

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "../../src/nodelets/blob_conversions.h"
#include "rle_vision/segment/segmenter.h"

namespace rle_vision {
namespace {

TEST(BlobConversions, CmvisionEdgesFollowCmvisionOnAKnownBox) {
  ColorClass red;
  red.name = "red";
  red.space = ColorSpace::RGB;
  red.min = {200, 0, 0};
  red.max = {255, 60, 60};
  red.display_rgb = {255, 40, 40};
  const ColorTable table({red});
  cv::Mat image(40, 50, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::rectangle(image, cv::Rect(10, 5, 10, 10), cv::Scalar(20, 20, 230), cv::FILLED);  // x 10..19, y 5..14 (BGR)
  Segmenter segmenter;
  BlobTracker tracker;
  std::vector<Region> regions;
  std::vector<TrackedBlob> blobs;
  segmenter.segment(image, PixelFormat::BGR8, table, &regions);
  tracker.update(regions, 0.0, &blobs);
  ASSERT_EQ(blobs.size(), 1u);
  BlobArray array;
  array.image_width = 50;
  array.image_height = 40;
  array.blobs.push_back(blobToMsg(blobs[0], "red"));
  const Blob& own = array.blobs[0];
  EXPECT_EQ(own.left, 10u);
  EXPECT_EQ(own.right, 19u);  // inclusive
  EXPECT_EQ(own.top, 5u);
  EXPECT_EQ(own.bottom, 14u);
  EXPECT_TRUE(std::isnan(own.score)) << "no verifier: no score";
  TrackedBlob scored = blobs[0];
  scored.score = 0.75f;
  EXPECT_FLOAT_EQ(blobToMsg(scored, "red").score, 0.75f);
  const CmvisionBlobs cm = cmvisionBlobsMsg(array, table);
  ASSERT_EQ(cm.blob_count, 1u);
  const CmvisionBlob& b = cm.blobs[0];
  EXPECT_EQ(b.name, "red");
  EXPECT_EQ(b.area, 100u);
  // CMVision: x1 = first column, x2 = x + run length, y1 = first row, y2 = last run's row.
  EXPECT_EQ(b.left, 10u);
  EXPECT_EQ(b.right, 20u);
  EXPECT_EQ(b.top, 5u);
  EXPECT_EQ(b.bottom, 14u);
  // cmvision's rounding of the centroid (14.5, 9.5): rint(c + 0.5).
  EXPECT_EQ(b.x, 15u);
  EXPECT_EQ(b.y, 10u);
  EXPECT_EQ((std::vector<uint32_t>{b.red, b.green, b.blue}), (std::vector<uint32_t>{255, 40, 40}));
}

}  // namespace
}  // namespace rle_vision
