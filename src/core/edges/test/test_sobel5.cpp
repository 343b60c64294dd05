// The paper's 5x5 Sobel edge filter with known answers: OpenCV's own Sobel, exactly, and the
// edge image's scale.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/edges/sobel5.h"

namespace rle_vision {
namespace {

// OpenCV's 5x5 Sobel (reflect-101 borders): max over channels of Gx^2 + Gy^2.
cv::Mat opencvSquaredMagnitude(const cv::Mat& image) {
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  cv::Mat best = cv::Mat::zeros(image.size(), CV_32S);
  for (const cv::Mat& c : channels) {
    cv::Mat fx, fy, gx, gy;
    // Float derivatives of 8-bit data are exact integers (|G| <= 12240); square in int32.
    cv::Sobel(c, fx, CV_32F, 1, 0, 5, 1, 0, cv::BORDER_REFLECT_101);
    cv::Sobel(c, fy, CV_32F, 0, 1, 5, 1, 0, cv::BORDER_REFLECT_101);
    fx.convertTo(gx, CV_32S);
    fy.convertTo(gy, CV_32S);
    cv::Mat m2 = gx.mul(gx) + gy.mul(gy);
    best = cv::max(best, m2);
  }
  return best;
}

TEST(Sobel5, SquaredMagnitudeEqualsOpenCvExactly) {
  Sobel5 sobel;
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(37, 23), cv::Size(5, 5), cv::Size(3, 7), cv::Size(64, 2)}) {
    for (int channels : {3, 1}) {
      cv::Mat image(size, CV_8UC(channels));
      cv::RNG(size.area() + channels).fill(image, cv::RNG::UNIFORM, 0, 256);
      cv::Mat ours;
      sobel.maxSquaredMagnitude(image, &ours);
      EXPECT_EQ(cv::norm(ours, opencvSquaredMagnitude(image), cv::NORM_INF), 0.0)
          << size << " " << channels << " channels";
    }
  }
}

TEST(Sobel5, SquaredMagnitudeIsExactAtTheLargestGradients) {
  // 0/255 steps and binary noise reach |Gx|, |Gy| = 12240, the bound the 16-bit lanes rely on.
  cv::Mat vertical_step(32, 32, CV_8UC3, cv::Scalar::all(0)), diagonal(32, 32, CV_8UC1, cv::Scalar(0));
  vertical_step.colRange(16, 32).setTo(cv::Scalar::all(255));
  for (int y = 0; y < diagonal.rows; ++y) diagonal.row(y).colRange(0, y).setTo(255);
  cv::Mat noise(240, 320, CV_8UC3);
  cv::RNG(7).fill(noise, cv::RNG::UNIFORM, 0, 2);
  noise *= 255;
  Sobel5 sobel;
  cv::Mat ours;
  for (const cv::Mat& image : {vertical_step, cv::Mat(vertical_step.t()), diagonal, noise}) {
    sobel.maxSquaredMagnitude(image, &ours);
    const cv::Mat expected = opencvSquaredMagnitude(image);
    EXPECT_EQ(cv::norm(ours, expected, cv::NORM_INF), 0.0) << image.size << " " << image.channels() << " channels";
    double largest = 0;
    cv::minMaxLoc(expected, nullptr, &largest);
    EXPECT_GE(largest, 12240.0 * 12240.0);
  }
}

TEST(Sobel5, EdgesAreTheScaledMagnitude) {
  cv::Mat image(48, 64, CV_8UC3, cv::Scalar(10, 20, 30));
  image(cv::Rect(32, 0, 32, 48)).setTo(cv::Scalar(10, 20, 130));  // a step of 100 in red
  Sobel5 sobel;
  cv::Mat edges;
  sobel.edges(image, 1.0, &edges);
  EXPECT_EQ(edges.at<uint8_t>(20, 31), 100);  // gain 1: a step of h gives h at the step
  EXPECT_EQ(edges.at<uint8_t>(20, 32), 100);
  EXPECT_EQ(edges.at<uint8_t>(20, 10), 0);
  sobel.edges(image, 3.0, &edges);
  EXPECT_EQ(edges.at<uint8_t>(20, 31), 255);  // saturates
  EXPECT_THROW(sobel.edges(cv::Mat(4, 4, CV_16UC1), 1.0, &edges), std::invalid_argument);
  EXPECT_THROW(sobel.edges(image, std::nan(""), &edges), std::invalid_argument);
}

}  // namespace
}  // namespace rle_vision
