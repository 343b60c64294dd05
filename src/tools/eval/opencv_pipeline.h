// The OpenCV way of doing the tracker's job, used as the benchmark baseline and as an
// independent check of our blobs: cvtColor to the classes' space, inRange per class,
// connectedComponentsWithStats per class, the same minimum area.
#pragma once

#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/color/color_convert.h"

namespace rle_vision {

struct OpenCvBlob {
  int label;  // 1 + class index
  int area;
  double cx, cy;
  cv::Rect bbox;
};

class OpenCvPipeline {
 public:
  // YUV classes without wrapped ranges (what inRange can express).
  explicit OpenCvPipeline(const std::vector<ColorClass>& classes, int connectivity = 8)
      : classes_(classes), connectivity_(connectivity) {
    for (const ColorClass& c : classes_) {
      if (c.space != ColorSpace::YUV) throw std::invalid_argument("OpenCvPipeline: YUV classes only");
      for (int ch = 0; ch < 3; ++ch) {
        if (c.min[ch] > c.max[ch]) throw std::invalid_argument("OpenCvPipeline: no wrapped ranges");
      }
    }
  }

  void run(const cv::Mat& bgr, std::vector<OpenCvBlob>* blobs) {
    blobs->clear();
    cv::cvtColor(bgr, yuv_, cv::COLOR_BGR2YUV);
    for (size_t k = 0; k < classes_.size(); ++k) {
      const ColorClass& c = classes_[k];
      cv::inRange(yuv_, cv::Scalar(c.min[0], c.min[1], c.min[2]), cv::Scalar(c.max[0], c.max[1], c.max[2]), mask_);
      const int n = cv::connectedComponentsWithStats(mask_, labels_, stats_, centroids_, connectivity_, CV_32S);
      for (int i = 1; i < n; ++i) {
        const int area = stats_.at<int>(i, cv::CC_STAT_AREA);
        if (area < static_cast<int>(c.min_area_px)) continue;
        blobs->push_back({static_cast<int>(k) + 1, area, centroids_.at<double>(i, 0), centroids_.at<double>(i, 1),
                          cv::Rect(stats_.at<int>(i, cv::CC_STAT_LEFT), stats_.at<int>(i, cv::CC_STAT_TOP),
                                   stats_.at<int>(i, cv::CC_STAT_WIDTH), stats_.at<int>(i, cv::CC_STAT_HEIGHT))});
      }
    }
  }

 private:
  std::vector<ColorClass> classes_;
  int connectivity_;
  cv::Mat yuv_, mask_, labels_, stats_, centroids_;
};

}  // namespace rle_vision
