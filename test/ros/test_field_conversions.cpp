// The field boundary in message form and back: the points survive the round trip; a message a
// broken publisher could send (NaN, points out of order, found with no points) is no boundary,
// so the tracker drops nothing by it.
#include <cmath>

#include <gtest/gtest.h>

#include "../../src/nodelets/field_conversions.h"

namespace rle_vision {
namespace {

TEST(FieldConversions, RoundTripAndBrokenMessagesAreNoBoundary) {
  FieldBoundaryEstimate boundary;
  boundary.found = true;
  boundary.confidence = 0.75;
  boundary.polyline = {{2, 120}, {300, 90.5f}, {638, 131}};
  std_msgs::Header header;
  header.stamp = ros::Time(12, 5);
  const FieldBoundary msg = fieldBoundaryToMsg(header, boundary);
  EXPECT_EQ(msg.header.stamp, header.stamp);
  ASSERT_EQ(msg.points.size(), 3u);
  const FieldBoundaryEstimate back = fieldBoundaryFromMsg(msg);
  EXPECT_TRUE(back.found);
  EXPECT_FLOAT_EQ(back.confidence, 0.75);
  ASSERT_EQ(back.polyline.size(), 3u);
  EXPECT_EQ(back.polyline[1], cv::Point2f(300, 90.5f));
  EXPECT_DOUBLE_EQ(back.rowAt(151), 105.25);

  FieldBoundary broken = msg;
  broken.points[1].y = std::nanf("");
  EXPECT_FALSE(fieldBoundaryFromMsg(broken).found);
  broken = msg;
  std::swap(broken.points[0], broken.points[2]);
  EXPECT_FALSE(fieldBoundaryFromMsg(broken).found);
  broken = msg;
  broken.points.clear();
  EXPECT_FALSE(fieldBoundaryFromMsg(broken).found);
  broken = msg;
  broken.found = false;
  EXPECT_FALSE(fieldBoundaryFromMsg(broken).found);
}

}  // namespace
}  // namespace rle_vision
