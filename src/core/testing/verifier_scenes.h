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

#include "rle_vision/color/color_class.h"

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

// A floor with a fringe, for the floor guard (verifier_training.h, floorGuardScalesTried): the
// floor learned as its colour +-15 on every YUV channel; strips 17 levels brighter (a line's
// fringe, a vignetted edge), beyond that range but inside it grown 1.5 times (+-22.5); balls and
// upright bars 40 levels brighter, beyond it grown 2.5 times (+-37.5) but inside it grown 3 times
// (+-45). One ball sits at a strip's end, where, with nothing taking the strip, it is one
// candidate with it, centred off the ball; the other ball and the bar stand free. `permissive`
// holds the strips, the balls and the bars.
struct FringeScene {
  ColorClass floor, permissive;
};

inline cv::Scalar floorYuv() {
  cv::Mat yuv;
  cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar(60, 120, 70)), yuv, cv::COLOR_BGR2YUV);
  const cv::Vec3b v = yuv.at<cv::Vec3b>(0);
  return cv::Scalar(v[0], v[1], v[2]);
}

// The floor's colour brightened by `dy` levels of Y, as BGR.
inline cv::Scalar floorBrightenedBy(int dy) {
  const cv::Scalar f = floorYuv();
  cv::Mat bgr;
  cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar(f[0] + dy, f[1], f[2])), bgr, cv::COLOR_YUV2BGR);
  const cv::Vec3b b = bgr.at<cv::Vec3b>(0);
  return cv::Scalar(b[0], b[1], b[2]);
}

inline FringeScene fringeScene() {
  const cv::Scalar f = floorYuv();
  FringeScene s;
  s.floor.name = "field";
  s.permissive.name = "ball";
  for (int c = 0; c < 3; ++c) {
    s.floor.min[c] = static_cast<uint8_t>(f[c] - 15);
    s.floor.max[c] = static_cast<uint8_t>(f[c] + 15);
    s.permissive.min[c] = static_cast<uint8_t>(c == 0 ? f[c] + 8 : f[c] - 20);
    s.permissive.max[c] = static_cast<uint8_t>(c == 0 ? f[c] + 70 : f[c] + 20);
  }
  return s;
}

inline VerifierFrame drawFringeFrame(cv::RNG& rng) {
  VerifierFrame f;
  f.bgr = cv::Mat(240, 320, CV_8UC3, floorBrightenedBy(0));
  const cv::Scalar bright = floorBrightenedBy(40);
  // Two strips, the first ending in a ball.
  const int y1 = rng.uniform(30, 90), x1 = rng.uniform(10, 40), y2 = rng.uniform(150, 200);
  cv::rectangle(f.bgr, cv::Rect(x1, y1, 80, 6), floorBrightenedBy(17), cv::FILLED);
  cv::rectangle(f.bgr, cv::Rect(rng.uniform(10, 60), y2, 80, 6), floorBrightenedBy(17), cv::FILLED);
  const int r1 = rng.uniform(7, 11), r2 = rng.uniform(7, 11);
  const cv::Point at_strip(x1 + 80 + r1 - 1, y1 + 3), free_ball(rng.uniform(200, 300), rng.uniform(150, 225));
  cv::circle(f.bgr, at_strip, r1, bright, cv::FILLED);
  cv::circle(f.bgr, free_ball, r2, bright, cv::FILLED);
  cv::rectangle(f.bgr, cv::Rect(rng.uniform(230, 300), rng.uniform(20, 80), 5, 40), bright, cv::FILLED);  // a bar
  f.balls = {cv::Rect(at_strip.x - r1, at_strip.y - r1, 2 * r1 + 1, 2 * r1 + 1),
             cv::Rect(free_ball.x - r2, free_ball.y - r2, 2 * r2 + 1, 2 * r2 + 1)};
  cv::Mat noise(f.bgr.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1.5);
  f.bgr += noise;
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
