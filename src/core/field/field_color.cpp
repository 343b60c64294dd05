#include "rle_vision/field/field_color.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "rle_vision/color/color_convert.h"

namespace rle_vision {
namespace {

using Histogram = std::array<uint32_t, 256>;

// The lower median of a histogram of `total` values.
int histogramMedian(const Histogram& h, size_t total) {
  size_t seen = 0;
  for (int v = 0; v < 256; ++v) {
    seen += h[v];
    if (2 * seen >= total) return v;
  }
  return 255;
}

// Medians and robust spreads (1.4826 x median absolute deviation) of per-channel histograms.
ChannelStats statsOf(const std::array<Histogram, 3>& h, size_t pixels) {
  ChannelStats s;
  s.pixels = pixels;
  if (pixels == 0) return s;
  for (int c = 0; c < 3; ++c) {
    const int median = histogramMedian(h[c], pixels);
    Histogram deviation{};
    for (int v = 0; v < 256; ++v) deviation[std::abs(v - median)] += h[c][v];
    s.median[c] = median;
    s.sigma[c] = 1.4826 * histogramMedian(deviation, pixels);
  }
  return s;
}

// Statistics of the pixels of `yuv` in rows [row0, rows) that `keep(y, u, v, x, row)` accepts.
template <class Keep>
ChannelStats measure(const cv::Mat& yuv, int row0, Keep keep) {
  std::array<Histogram, 3> h{};
  size_t pixels = 0;
  for (int r = row0; r < yuv.rows; ++r) {
    const uint8_t* p = yuv.ptr<uint8_t>(r);
    for (int x = 0; x < yuv.cols; ++x, p += 3) {
      if (!keep(p[0], p[1], p[2], x, r)) continue;
      ++h[0][p[0]];
      ++h[1][p[1]];
      ++h[2][p[2]];
      ++pixels;
    }
  }
  return statsOf(h, pixels);
}

// The range grown to twice its width about its centre: where this frame's field pixels are
// looked for (the light may have moved them).
ColorClass grown(const ColorClass& range) {
  ColorClass g = range;
  for (int c = 0; c < 3; ++c) {
    const int half = (range.max[c] - range.min[c] + 1) / 2;
    g.min[c] = saturateToByte(range.min[c] - half);
    g.max[c] = saturateToByte(range.max[c] + half);
  }
  return g;
}

}  // namespace

cv::Mat fieldYuv(const cv::Mat& bgr) { return convertBgrImage(bgr, ColorSpace::YUV); }

cv::Mat fieldYuvColumns(const cv::Mat& bgr, int first_x, int step_x) {
  step_x = std::max(1, step_x);
  const int columns = bgr.cols > first_x ? (bgr.cols - first_x + step_x - 1) / step_x : 0;
  cv::Mat out(bgr.rows, columns, CV_8UC3);
  for (int r = 0; r < bgr.rows; ++r) {
    const uint8_t* in = bgr.ptr<uint8_t>(r) + 3 * first_x;
    uint8_t* o = out.ptr<uint8_t>(r);
    for (int j = 0; j < columns; ++j, in += 3 * step_x, o += 3) {
      const Channels yuv = yuvFromRgb(in[2], in[1], in[0]);
      o[0] = yuv[0], o[1] = yuv[1], o[2] = yuv[2];
    }
  }
  return out;
}

int FieldColorModel::bandStart(int rows) const {
  return std::min(rows - 1, static_cast<int>(std::floor(rows * (1.0 - options_.seed_band_share))));
}

ColorClass FieldColorModel::rangeFrom(const ChannelStats& stats) const {
  ColorClass range;
  range.name = "field";
  range.space = ColorSpace::YUV;
  range.source = "learned";
  for (int c = 0; c < 3; ++c) {
    const double half = std::max(options_.min_half_width, options_.range_sigmas * stats.sigma[c]);
    range.min[c] = saturateToByte(static_cast<int>(std::floor(stats.median[c] - half)));
    range.max[c] = saturateToByte(static_cast<int>(std::ceil(stats.median[c] + half)));
  }
  range.display_rgb = {{40, 160, 60}};
  return range;
}

FieldColor FieldColorModel::seed(const cv::Mat& yuv) const {
  FieldColor result;
  if (yuv.empty() || yuv.type() != CV_8UC3) return result;
  const int row0 = bandStart(yuv.rows);
  const int bin = std::max(1, options_.chroma_bin), bins = (255 / bin) + 1;
  // The chroma histogram's mode (counts summed over each bin's 3x3 neighbourhood).
  std::vector<uint32_t> chroma(static_cast<size_t>(bins) * bins, 0);
  size_t band = 0;
  for (int r = row0; r < yuv.rows; ++r) {
    const uint8_t* p = yuv.ptr<uint8_t>(r);
    for (int x = 0; x < yuv.cols; ++x, p += 3) ++chroma[(p[1] / bin) * bins + p[2] / bin];
    band += yuv.cols;
  }
  uint64_t best = 0;
  int best_u = 0, best_v = 0;
  for (int bu = 0; bu < bins; ++bu) {
    for (int bv = 0; bv < bins; ++bv) {
      uint64_t sum = 0;
      for (int du = -1; du <= 1; ++du) {
        for (int dv = -1; dv <= 1; ++dv) {
          const int u = bu + du, v = bv + dv;
          if (u >= 0 && u < bins && v >= 0 && v < bins) sum += chroma[u * bins + v];
        }
      }
      if (sum > best) best = sum, best_u = bu, best_v = bv;
    }
  }
  // The mode's pixels, then the pixels in the range they give, a few times: the range widens
  // to the mode's own spread (a Gaussian cut at +-3 sigma keeps its median and nearly its MAD)
  // but not into neighbouring colours, which lie beyond the cut.
  const double cu = (best_u + 0.5) * bin, cv_ = (best_v + 0.5) * bin, reach = 1.5 * bin;
  ChannelStats stats = measure(yuv, row0, [&](uint8_t, uint8_t u, uint8_t v, int, int) {
    return std::fabs(u - cu) <= reach && std::fabs(v - cv_) <= reach;
  });
  ColorClass range = rangeFrom(stats);
  for (int round = 0; round < 4; ++round) {
    stats = measure(yuv, row0, [&](uint8_t y, uint8_t u, uint8_t v, int, int) { return range.contains({{y, u, v}}); });
    range = rangeFrom(stats);
  }
  const ChannelStats kept =
      measure(yuv, row0, [&](uint8_t y, uint8_t u, uint8_t v, int, int) { return range.contains({{y, u, v}}); });
  result.range = range;
  result.share = band ? static_cast<double>(kept.pixels) / band : 0.0;
  result.found = result.share >= options_.min_share;
  return result;
}

FieldColor FieldColorModel::update(const FieldColor& current, const cv::Mat& yuv, const cv::Mat& field_mask) const {
  if (!current.found || yuv.empty() || field_mask.size() != yuv.size() || field_mask.type() != CV_8UC1) return current;
  const ColorClass wider = grown(current.range);
  const ChannelStats stats = measure(yuv, 0, [&](uint8_t y, uint8_t u, uint8_t v, int x, int r) {
    return field_mask.at<uint8_t>(r, x) != 0 && wider.contains({{y, u, v}});
  });
  const size_t region = static_cast<size_t>(cv::countNonZero(field_mask));
  if (stats.pixels == 0 || region == 0) return current;
  const ColorClass measured = rangeFrom(stats);
  FieldColor next = current;
  for (int c = 0; c < 3; ++c) {
    const double b = options_.blend;
    next.range.min[c] = saturateToByte(static_cast<int>(std::lround((1 - b) * current.range.min[c] + b * measured.min[c])));
    next.range.max[c] = saturateToByte(static_cast<int>(std::lround((1 - b) * current.range.max[c] + b * measured.max[c])));
  }
  const ChannelStats kept = measure(yuv, 0, [&](uint8_t y, uint8_t u, uint8_t v, int x, int r) {
    return field_mask.at<uint8_t>(r, x) != 0 && next.range.contains({{y, u, v}});
  });
  next.share = static_cast<double>(kept.pixels) / region;
  return next;
}

cv::Mat FieldColorModel::mask(const cv::Mat& yuv, const ColorClass& range) {
  cv::Mat out;
  cv::inRange(yuv, cv::Scalar(range.min[0], range.min[1], range.min[2]), cv::Scalar(range.max[0], range.max[1], range.max[2]),
              out);
  return out;
}

}  // namespace rle_vision
