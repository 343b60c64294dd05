// What the verifier judges a candidate blob by: the blob as the tracker found it (size, fill,
// shape, where it lies in the view) and the image around it (its box's colour and its ring's,
// a small appearance descriptor of the box plus a margin: gradient orientations on grey, and
// coarse chroma). Computed from the frame and the Region only, so that training and run time see
// exactly the same thing. Chroma is measured against the frame's own (FrameChroma).
#pragma once

#include <array>

#include <opencv2/core.hpp>

#include "rle_vision/segment/regions.h"

namespace rle_vision {

// Blob 6, box colour 6, ring colour 3, box minus ring 3, gradient orientations 32, chroma 32.
constexpr int kCandidateFeatureCount = 82;
// What the features mean; a model file records it. 2: chroma relative to the frame's.
constexpr int kCandidateFeatureVersion = 2;
using CandidateFeatures = std::array<float, kCandidateFeatureCount>;

// The frame's chroma: the median U and V (YUV as OpenCV's COLOR_BGR2YUV) of a 48x48 grid of its
// pixels. A hall's light tints every colour of the scene alike (grey world): the
// candidates' chroma is measured from this, so that what a model learned under one light holds
// under another. One per frame, before its candidates.
struct FrameChroma {
  double u = 128, v = 128;
};
FrameChroma frameChroma(const cv::Mat& bgr);

// The features of `region` (a blob of `bgr`, CV_8UC3, whose chroma is `frame`). `patch_bgr`,
// `patch_yuv`: scratch buffers (reuse them across calls). Throws std::invalid_argument when the
// frame is not CV_8UC3 or the region's box lies off it.
void candidateFeatures(const cv::Mat& bgr, const FrameChroma& frame, const Region& region, CandidateFeatures* out,
                       cv::Mat* patch_bgr = nullptr, cv::Mat* patch_yuv = nullptr);

}  // namespace rle_vision
