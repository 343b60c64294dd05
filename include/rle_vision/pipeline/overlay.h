// Debug overlays (drawn only while someone looks: a ~debug_image subscriber, or
// rle_vision_detect --annotate).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/learning/color_learning.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/landmark/horizon_finder.h"
#include "rle_vision/color/pixel_format.h"
#include "rle_vision/landmark/detected_line.h"
#include "rle_vision/field/field_boundary.h"

namespace rle_vision {

// A BGR copy of an input image for drawing on.
cv::Mat toDisplayBgr(const cv::Mat& image, PixelFormat format);
// The same into *bgr, whose buffer is reused when it has the size and type already.
void toDisplayBgr(const cv::Mat& image, PixelFormat format, cv::Mat* bgr);

// Blob boxes in their class's display colour, with "id class" labels.
void drawBlobs(cv::Mat* canvas, const std::vector<TrackedBlob>& blobs, const ColorTable& table);

// One swatch per colour class along the bottom edge: left half its display colour, right half
// the colour at the centre of its range; learned classes are marked with '*'.
void drawColorSwatches(cv::Mat* canvas, const ColorTable& table);

// The regions colour learning measured: accepted in white, refused in red with the reason.
void drawLearning(cv::Mat* canvas, const std::vector<ColorLearner::Measurement>& measurements);

// Lines in green, the horizon in thick cyan with its roll and pitch (rad; pitch may be NaN).
void drawLandmarks(cv::Mat* canvas, const std::vector<DetectedLine>& lines, const HorizonEstimate& horizon,
                   double roll, double pitch);

// The field boundary as a thick orange polyline with its confidence (or "no field boundary").
void drawFieldBoundary(cv::Mat* canvas, const FieldBoundaryEstimate& boundary);

}  // namespace rle_vision
