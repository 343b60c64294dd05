// Drawing of debug overlays (only done while someone subscribes to a ~debug_image).
#pragma once

#include <opencv2/core.hpp>
#include <sensor_msgs/Image.h>

#include "rle_vision/BlobArray.h"
#include "rle_vision/color_table.h"
#include "rle_vision/pixel_format.h"

namespace rle_vision {

// A BGR copy of an input image for drawing on.
cv::Mat toDisplayBgr(const cv::Mat& image, PixelFormat format);

// Blob boxes in their class's display colour, with "id color" labels.
void drawBlobs(cv::Mat* canvas, const BlobArray& blobs, const ColorTable& table);

// One swatch per colour class along the bottom edge: left half its display colour, right half
// the colour at the centre of its range; learned classes are marked with '*'.
void drawColorSwatches(cv::Mat* canvas, const ColorTable& table);

sensor_msgs::ImagePtr debugImageMsg(const std_msgs::Header& header, const cv::Mat& bgr);

}  // namespace rle_vision
