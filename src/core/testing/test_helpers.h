// Shared fixtures for the core tests.
#pragma once

#include <string>
#include <vector>

#include "rle_vision/color/color_class.h"

namespace rle_vision {
namespace test {

inline std::string sourcePath(const std::string& relative) {
  return std::string(RLE_VISION_SOURCE_DIR) + "/" + relative;
}

inline ColorClass makeClass(const std::string& name, ColorSpace space, Channels lo, Channels hi,
                            uint32_t min_area = 1) {
  ColorClass c;
  c.name = name;
  c.space = space;
  c.min = lo;
  c.max = hi;
  c.min_area_px = min_area;
  return c;
}

}  // namespace test
}  // namespace rle_vision

#include <cmath>
#include <limits>

#include "rle_vision/color/color_table.h"
#include "rle_vision/segment/regions.h"
#include "rle_vision/sim/scene_simulator.h"

namespace rle_vision {
namespace test {

// The region of the box's colour class whose centroid is nearest the box's true centroid, or
// nullptr when there is none within `max_distance_px`.
inline const Region* regionOfBox(const std::vector<Region>& regions, const ColorTable& table,
                                 const BoxTruth& box, double max_distance_px) {
  const int label = table.indexOf(box.color_class) + 1;
  const Region* best = nullptr;
  double best_distance = max_distance_px;
  for (const Region& r : regions) {
    if (r.label != label) continue;
    const double d = std::hypot(r.cx - box.cx, r.cy - box.cy);
    if (d <= best_distance) {
      best_distance = d;
      best = &r;
    }
  }
  return best;
}

}  // namespace test
}  // namespace rle_vision

#include <opencv2/imgproc.hpp>

namespace rle_vision {
namespace test {

// The exact answer a colour segmenter should give on a noise-free simulator frame: for each
// class, the 8-connected components of the union of its boxes' rendered masks (boxes of one
// colour that touch in the image are one blob; a box split by an occluder is two).
inline std::vector<Region> truthRegions(const SimFrame& frame, const ColorTable& table) {
  std::vector<Region> regions;
  for (int k = 0; k < table.size(); ++k) {
    cv::Mat mask = cv::Mat::zeros(frame.labels.size(), CV_8UC1);
    for (const BoxTruth& box : frame.boxes) {
      if (box.color_class == table.classes()[k].name) mask |= frame.labels == box.label;
    }
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
    for (int i = 1; i < n; ++i) {
      Region r;
      r.label = k + 1;
      r.area = static_cast<uint32_t>(stats.at<int>(i, cv::CC_STAT_AREA));
      if (r.area < table.classes()[k].min_area_px) continue;
      r.cx = centroids.at<double>(i, 0);
      r.cy = centroids.at<double>(i, 1);
      r.left = stats.at<int>(i, cv::CC_STAT_LEFT);
      r.top = stats.at<int>(i, cv::CC_STAT_TOP);
      r.right = r.left + stats.at<int>(i, cv::CC_STAT_WIDTH) - 1;
      r.bottom = r.top + stats.at<int>(i, cv::CC_STAT_HEIGHT) - 1;
      regions.push_back(r);
    }
  }
  return regions;
}

// Boxes whose visible mask is by itself one whole blob (not merged with a same-coloured box,
// not split by an occluder): the ones whose blob centroid is the box's own centroid.
inline std::vector<BoxTruth> isolatedBoxes(const SimFrame& frame, const ColorTable& table) {
  std::vector<BoxTruth> out;
  const std::vector<Region> truth = truthRegions(frame, table);
  for (const BoxTruth& box : frame.boxes) {
    if (box.area == 0) continue;
    for (const Region& r : truth) {
      if (r.label == table.indexOf(box.color_class) + 1 && r.area == box.area &&
          std::hypot(r.cx - box.cx, r.cy - box.cy) < 1e-9) {
        out.push_back(box);
      }
    }
  }
  return out;
}

}  // namespace test
}  // namespace rle_vision
