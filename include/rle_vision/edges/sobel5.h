// The paper's 5x5 Sobel edge filter on every colour channel (eq. 1: S_v = S_h transposed):
// separable int16 passes (smoothing [1 4 6 4 1], derivative [-1 -2 0 2 1]), reflect-101
// borders as OpenCV's default. The edge value of a pixel is the largest channel gradient
// magnitude, scaled to mono8.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace rle_vision {

// The 5x5 kernels gain 48 on a unit step: a step of height h gives a peak magnitude of 48 h.
constexpr double kSobel5StepGain = 48.0;

// Holds row buffers; reuse one instance per thread.
class Sobel5 {
 public:
  // edges = saturate(round(edge_gain * sqrt(max_c(Gx_c^2 + Gy_c^2)) / 48)): with gain 1 a step
  // of height h in one channel gives an edge value of h. `image` is CV_8UC3 (any channel
  // order) or CV_8UC1; `edges` becomes CV_8UC1. Throws std::invalid_argument on other types.
  void edges(const cv::Mat& image, double edge_gain, cv::Mat* edges);
  // The unscaled max_c(Gx_c^2 + Gy_c^2) as CV_32S (for tests and calibration).
  void maxSquaredMagnitude(const cv::Mat& image, cv::Mat* magnitude2);

 private:
  template <typename Sink>
  void run(const cv::Mat& image, Sink sink);

  int width_ = 0, channels_ = 0;
  std::vector<int16_t> rows_;        // 5 padded planar rows per channel (ring)
  std::vector<int16_t> smooth_, derivative_;
  std::vector<int32_t> best_;
};

}  // namespace rle_vision
