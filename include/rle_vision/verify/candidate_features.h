// What the verifier judges a candidate blob by: the blob as the tracker found it (size, fill,
// shape, where it lies in the view) and the image around it (its box's colour and its ring's,
// a small appearance descriptor of the box plus a margin: gradient orientations on grey, and
// coarse chroma). Computed from the frame and the Region only, so that training and run time see
// exactly the same thing.
#pragma once

#include <array>

#include <opencv2/core.hpp>

#include "rle_vision/segment/regions.h"

namespace rle_vision {

// Blob 6, box colour 6, ring colour 3, box minus ring 3, gradient orientations 32, chroma 32.
constexpr int kCandidateFeatureCount = 82;
using CandidateFeatures = std::array<float, kCandidateFeatureCount>;

// The features of `region` (a blob of `bgr`, CV_8UC3). `patch_bgr`, `patch_yuv`: scratch
// buffers (reuse them across calls).
void candidateFeatures(const cv::Mat& bgr, const Region& region, CandidateFeatures* out, cv::Mat* patch_bgr = nullptr,
                       cv::Mat* patch_yuv = nullptr);

}  // namespace rle_vision
