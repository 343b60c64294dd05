#include "rle_vision/color/classifier.h"

#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_convert.h"
#include "common/simd_dispatch.h"
#include "color/yuv_classify_avx2.h"

namespace rle_vision {
namespace {

// labels[x] = label where all three channels lie in their (possibly wrapped) ranges.
// The unsigned modular compare needs no branch for wrapped ranges and vectorises well.
// Bitwise & (not &&) and __restrict keep the loop branch-free so it vectorises.
RLE_VISION_HOT
void applyClassBox(const uint8_t* __restrict c0, const uint8_t* __restrict c1,
                   const uint8_t* __restrict c2, int width, uint8_t lo0, uint8_t span0, uint8_t lo1,
                   uint8_t span1, uint8_t lo2, uint8_t span2, uint8_t label,
                   uint8_t* __restrict labels) {
  for (int x = 0; x < width; ++x) {
    const bool inside = (static_cast<uint8_t>(c0[x] - lo0) <= span0) &
                        (static_cast<uint8_t>(c1[x] - lo1) <= span1) &
                        (static_cast<uint8_t>(c2[x] - lo2) <= span2);
    labels[x] = inside ? label : labels[x];
  }
}

// Each pixel pair's mean, (a + b + 1) / 2, in both (a last odd pixel keeps its own).
void averagePairs(uint8_t* plane, int width) {
  for (int x = 0; x + 1 < width; x += 2) plane[x] = plane[x + 1] = pairMean(plane[x], plane[x + 1]);
}

}  // namespace

const YuvBoxes* PixelClassifier::yuvBoxesFor(const ColorTable& table) {
  if (table.classesIn(ColorSpace::YUV) != (table.size() == 32 ? ~0u : (1u << table.size()) - 1)) {
    return nullptr;  // some classes are in other spaces
  }
  if (!yuv_boxes_) yuv_boxes_ = std::make_shared<YuvBoxes>();
  if (yuv_boxes_serial_ != table.serial()) {
    YuvBoxes& boxes = *yuv_boxes_;
    boxes.count = table.size();
    for (int i = 0; i < boxes.count; ++i) {
      const int k = boxes.count - 1 - i;  // lowest priority first: the first class wins
      const ColorClass& c = table.classes()[k];
      for (int ch = 0; ch < 3; ++ch) {
        boxes.lo[i][ch] = c.min[ch];
        boxes.span[i][ch] = static_cast<uint8_t>(c.max[ch] - c.min[ch]);
      }
      boxes.label[i] = static_cast<uint8_t>(k + 1);
    }
    yuv_boxes_serial_ = table.serial();
  }
  return yuv_boxes_.get();
}

void PixelClassifier::ensureWidth(int width) {
  if (width <= width_) return;
  width_ = width;
  for (auto& space : planes_) {
    for (auto& plane : space) plane.resize(width);
  }
  scratch_.resize(3 * static_cast<size_t>(width));
  bgr_scratch_.resize(3 * static_cast<size_t>(width));
}

void PixelClassifier::planesFromRgbRow(const uint8_t* src, int width, bool src_is_rgb,
                                       const ColorTable& table, bool with_yuv) {
  if (with_yuv && table.classesIn(ColorSpace::YUV)) {
    auto& p = planes_[static_cast<int>(ColorSpace::YUV)];
    bgrRowToYuvPlanes(src, width, src_is_rgb, p[0].data(), p[1].data(), p[2].data());
  }
  if (table.classesIn(ColorSpace::RGB)) {
    auto& p = planes_[static_cast<int>(ColorSpace::RGB)];
    bgrRowToRgbPlanes(src, width, src_is_rgb, p[0].data(), p[1].data(), p[2].data());
  }
  if (table.classesIn(ColorSpace::HSV)) {
    // HSV needs a division per pixel; OpenCV's converter is well vectorised, reuse it.
    const cv::Mat row(1, width, CV_8UC3, const_cast<uint8_t*>(src));
    cv::Mat hsv(1, width, CV_8UC3, scratch_.data());
    cv::cvtColor(row, hsv, src_is_rgb ? cv::COLOR_RGB2HSV : cv::COLOR_BGR2HSV);
    auto& p = planes_[static_cast<int>(ColorSpace::HSV)];
    interleavedRowToPlanes(scratch_.data(), width, p[0].data(), p[1].data(), p[2].data());
  }
}

void PixelClassifier::classifyRow(const uint8_t* src, int width, PixelFormat format,
                                  const ColorTable& table, uint8_t* labels) {
  ensureWidth(width);
  if (format == PixelFormat::MONO8) {
    for (int x = 0; x < width; ++x) labels[x] = static_cast<uint8_t>(firstClassLabel(table.monoMask(src[x])));
    return;
  }
  if (format == PixelFormat::BGR8 || format == PixelFormat::RGB8) {
    if (yuvClassifyAvx2Available()) {
      if (const YuvBoxes* boxes = yuvBoxesFor(table)) {
        classifyRowYuvAvx2(src, width, format == PixelFormat::RGB8, bgr_pair_chroma_, *boxes, labels);
        return;
      }
    }
    planesFromRgbRow(src, width, format == PixelFormat::RGB8, table, /*with_yuv=*/true);
    if (bgr_pair_chroma_ && table.classesIn(ColorSpace::YUV)) {
      auto& p = planes_[static_cast<int>(ColorSpace::YUV)];
      averagePairs(p[1].data(), width);
      averagePairs(p[2].data(), width);
    }
  } else {  // 4:2:2
    const bool is_uyvy = format == PixelFormat::UYVY;
    if (yuvClassifyAvx2Available()) {
      if (const YuvBoxes* boxes = yuvBoxesFor(table)) {
        classifyRowYuv422Avx2(src, width, is_uyvy, *boxes, labels);
        return;
      }
    }
    if (table.classesIn(ColorSpace::YUV)) {
      auto& p = planes_[static_cast<int>(ColorSpace::YUV)];
      yuv422RowToPlanes(src, width, is_uyvy, p[0].data(), p[1].data(), p[2].data());
    }
    if (table.classesIn(ColorSpace::RGB) || table.classesIn(ColorSpace::HSV)) {
      // Other spaces go through BGR; the YUV planes keep the camera's own values.
      const cv::Mat row(1, width, CV_8UC2, const_cast<uint8_t*>(src));
      cv::Mat bgr_row(1, width, CV_8UC3, bgr_scratch_.data());
      cv::cvtColor(row, bgr_row, is_uyvy ? cv::COLOR_YUV2BGR_UYVY : cv::COLOR_YUV2BGR_YUY2);
      planesFromRgbRow(bgr_scratch_.data(), width, false, table, /*with_yuv=*/false);
    }
  }
  // Highest index first, so where classes overlap the first one listed wins.
  std::fill(labels, labels + width, uint8_t{0});
  for (int k = table.size() - 1; k >= 0; --k) {
    const ColorClass& c = table.classes()[k];
    const auto& p = planes_[static_cast<int>(c.space)];
    applyClassBox(p[0].data(), p[1].data(), p[2].data(), width, c.min[0],
                  static_cast<uint8_t>(c.max[0] - c.min[0]), c.min[1],
                  static_cast<uint8_t>(c.max[1] - c.min[1]), c.min[2],
                  static_cast<uint8_t>(c.max[2] - c.min[2]), static_cast<uint8_t>(k + 1), labels);
  }
}

cv::Mat PixelClassifier::classify(const cv::Mat& image, PixelFormat format, const ColorTable& table) {
  const std::string problem = checkImage(image, format);
  if (!problem.empty()) throw std::invalid_argument(problem);
  cv::Mat labels(image.rows, image.cols, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    classifyRow(image.ptr<uint8_t>(y), image.cols, format, table, labels.ptr<uint8_t>(y));
  }
  return labels;
}

cv::Mat colorClassMask(const ColorClass& c, const cv::Mat& bgr) {
  PixelClassifier classifier;
  return classifier.classify(bgr, PixelFormat::BGR8, ColorTable({c})) == 1;
}

}  // namespace rle_vision
