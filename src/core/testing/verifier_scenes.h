// Synthetic frames for the verifier's tests: a floor with a shaded ball (lit from above: its
// lower part darker) and, in the same yellow, an upright bar and a ragged patch, at seeded
// places (anywhere across the view) and sizes; the ball's box is the label.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace rle_vision {
namespace test {

struct VerifierFrame {
  cv::Mat bgr;
  std::vector<cv::Rect> balls;
};

inline VerifierFrame drawVerifierFrame(cv::RNG& rng) {
  const cv::Scalar yellow(40, 200, 230);  // BGR
  VerifierFrame f;
  f.bgr = cv::Mat(240, 320, CV_8UC3, cv::Scalar(60, 120, 70));
  cv::Mat noise(f.bgr.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::NORMAL, 0, 4);
  f.bgr += noise;
  // The ball, the bar and the patch each in one third of the width, the thirds shuffled: where a
  // candidate lies tells nothing of what it is.
  int third[3] = {0, 1, 2};
  for (int i = 2; i > 0; --i) std::swap(third[i], third[rng.uniform(0, i + 1)]);
  auto x_in = [&rng](int t, int margin) { return t * 107 + margin + rng.uniform(0, 107 - 2 * margin); };
  const int radius = rng.uniform(6, 16);
  const cv::Point centre(x_in(third[0], 17), rng.uniform(40, 220));
  for (int r = radius; r > 0; --r) {  // darker towards the bottom right: a lit crescent
    const double shade = 0.55 + 0.45 * r / radius;
    cv::circle(f.bgr, centre + cv::Point((radius - r) / 2, (radius - r) / 2), r, yellow * shade, cv::FILLED, cv::LINE_AA);
  }
  cv::circle(f.bgr, centre - cv::Point(radius / 3, radius / 3), std::max(1, radius / 4), yellow, cv::FILLED);
  f.balls.push_back(cv::Rect(centre.x - radius, centre.y - radius, 2 * radius + 1, 2 * radius + 1));
  const int bar_w = rng.uniform(5, 10);
  cv::rectangle(f.bgr, cv::Rect(x_in(third[1], 12), rng.uniform(20, 120), bar_w, bar_w * rng.uniform(4, 8)), yellow,
                cv::FILLED);
  std::vector<cv::Point> patch;
  const cv::Point at(x_in(third[2], 28), rng.uniform(60, 200));
  for (int k = 0; k < 9; ++k) {
    const double a = k * 2 * M_PI / 9, r = rng.uniform(10, 28);
    patch.emplace_back(at + cv::Point(static_cast<int>(r * std::cos(a)), static_cast<int>(r * std::sin(a))));
  }
  cv::fillPoly(f.bgr, std::vector<std::vector<cv::Point>>{patch}, yellow * 0.9);
  return f;
}

// Writes `frames` frames drawn from `seed` into the existing `folder` as frame_I.png with a YOLO
// label file frame_I.txt beside each (class 0: the ball; empty files when `labels` is false).
// Returns "" or what could not be written.
inline std::string writeVerifierFolder(const std::string& folder, int frames, uint64_t seed, bool labels = true) {
  cv::RNG rng(seed);
  for (int i = 0; i < frames; ++i) {
    const VerifierFrame f = drawVerifierFrame(rng);
    const std::string name = folder + "/frame_" + std::to_string(i);
    if (!cv::imwrite(name + ".png", f.bgr)) return "cannot write " + name + ".png";
    std::ofstream label(name + ".txt");
    for (const cv::Rect& b : f.balls) {
      if (!labels) continue;
      label << "0 " << (b.x + 0.5 * b.width) / f.bgr.cols << " " << (b.y + 0.5 * b.height) / f.bgr.rows << " "
            << static_cast<double>(b.width) / f.bgr.cols << " " << static_cast<double>(b.height) / f.bgr.rows << "\n";
    }
    if (!label) return "cannot write " + name + ".txt";
  }
  return "";
}

}  // namespace test
}  // namespace rle_vision
