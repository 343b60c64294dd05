#include "rle_vision/segment/segmenter.h"

#include <algorithm>
#include <stdexcept>

namespace rle_vision {

void Segmenter::segment(const cv::Mat& image, PixelFormat format, const ColorTable& table,
                        std::vector<Region>* regions) {
  const std::string problem = checkImage(image, format);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const int width = image.cols;
  const int height = image.rows;
  labels_.resize(static_cast<size_t>(width));
  runs_.clear();
  row_starts_.resize(static_cast<size_t>(height) + 1);
  classifier_.setBgrPairChroma(options_.bgr_pair_chroma);
  for (int y = 0; y < height; ++y) {
    row_starts_[y] = static_cast<int32_t>(runs_.size());
    classifier_.classifyRow(image.ptr<uint8_t>(y), width, format, table, labels_.data());
    row_encoder_.append(labels_.data(), width, y, &runs_, options_.flip_filter_px);
  }
  row_starts_[height] = static_cast<int32_t>(runs_.size());

  min_area_by_label_.assign(static_cast<size_t>(table.size()) + 1, options_.min_area_px);
  for (int k = 0; k < table.size(); ++k) {
    min_area_by_label_[k + 1] = std::max(options_.min_area_px, table.classes()[k].min_area_px);
  }
  builder_.build(&runs_, row_starts_, options_.connectivity, min_area_by_label_, regions);
}

}  // namespace rle_vision
