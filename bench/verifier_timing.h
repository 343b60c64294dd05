// The verifier's cost beside the tracker's (issue 30): the benchmark frame (640x480) with 50
// candidates of the shipped ball verifier's range drawn on it (discs of 3 to 12 px radius on a
// grid; the scene's own patches of that colour are candidates too), the tracker alone on that
// frame, and the verifier scoring the candidates up to its cap of 50, largest first.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "harness.h"
#include "rle_vision/color/color_convert.h"
#include "rle_vision/tracking/color_tracker.h"
#include "rle_vision/verify/candidate_screen.h"

namespace rle_vision {
namespace bench {

struct VerifierTimes {
  size_t candidates = 0;
  size_t scored = 0;       // at most the cap, 50
  double tracker_ms = 0;   // segment + tracker on the frame, all classes
  double verifier_ms = 0;  // the screen: features and score of every candidate
};

// A BGR colour whose YUV lies in the middle of `range` (a YUV class), found on a grid.
inline cv::Scalar bgrInside(const ColorClass& range) {
  int best = 1 << 30;
  cv::Scalar colour;
  for (int b = 0; b < 256; b += 3) {
    for (int g = 0; g < 256; g += 3) {
      for (int r = 0; r < 256; r += 3) {
        const Channels yuv = yuvFromRgb(r, g, b);
        int distance = 0;
        for (int c = 0; c < 3; ++c) distance += std::abs(2 * yuv[c] - range.min[c] - range.max[c]);
        if (distance < best) best = distance, colour = cv::Scalar(b, g, r);
      }
    }
  }
  return colour;
}

inline VerifierTimes timeVerifier(const cv::Mat& frame, std::vector<ColorClass> classes, const std::string& model_path) {
  const auto verifier = std::make_shared<const BlobVerifier>(BlobVerifier::load(model_path));
  ColorClass ball = verifier->candidateRange();
  classes.insert(classes.begin(), ball);
  const ColorTable table(classes);
  cv::Mat image = frame.clone();
  const cv::Scalar colour = bgrInside(ball);
  for (int i = 0; i < 50; ++i) {  // 10 x 5, in the upper part of the view (the sky) and below it
    const cv::Point centre(32 + 64 * (i % 10), 40 + 96 * (i / 10));
    cv::circle(image, centre, 3 + i % 10, colour, cv::FILLED);
  }
  ColorTracker tracker;
  std::vector<TrackedBlob> blobs, screened;
  double stamp = 0;
  VerifierTimes t;
  t.tracker_ms = medianMs([&] {
    tracker.process(image, PixelFormat::BGR8, table, stamp += 1.0 / 30, &blobs);
    keep(blobs);
  });
  CandidateScreen screen({{ball.name, verifier, 0.5}}, 50);
  t.candidates = static_cast<size_t>(std::count_if(blobs.begin(), blobs.end(),
                                                   [](const TrackedBlob& b) { return b.region.label == 1; }));
  ScreeningCounts counts;
  t.verifier_ms = medianMs([&] {
    screened = blobs;
    counts = screen.apply(image, table, &screened);
    keep(counts);
  });
  t.scored = counts.scored;
  return t;
}

}  // namespace bench
}  // namespace rle_vision
