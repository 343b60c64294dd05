// Whole-frame segmentation against exact ground truth.
#include <algorithm>
#include <cstdio>
#include <numeric>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_convert.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/segment/segmenter.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

using test::makeClass;
using test::regionOfBox;
using test::sourcePath;

TEST(Segmenter, RectanglesGiveExactStatistics) {
  const ColorTable table({makeClass("red", ColorSpace::RGB, {{200, 0, 0}}, {{255, 60, 60}}),
                          makeClass("blue", ColorSpace::RGB, {{0, 0, 200}}, {{60, 60, 255}})});
  cv::Mat image(120, 160, CV_8UC3, cv::Scalar(0, 128, 0));
  cv::rectangle(image, cv::Rect(10, 20, 30, 40), cv::Scalar(0, 0, 255), cv::FILLED);   // red
  cv::rectangle(image, cv::Rect(100, 5, 11, 7), cv::Scalar(255, 0, 0), cv::FILLED);    // blue
  cv::rectangle(image, cv::Rect(60, 90, 2, 2), cv::Scalar(255, 0, 0), cv::FILLED);     // 4 px blue
  Segmenter segmenter(SegmenterOptions{Connectivity::Eight, 5});
  std::vector<Region> regions;
  segmenter.segment(image, PixelFormat::BGR8, table, &regions);
  ASSERT_EQ(regions.size(), 2u);  // the 4-pixel square is below min_area_px
  const Region& blue = regions[0];  // raster order: the blue one starts on row 5
  EXPECT_EQ(blue.label, 2);
  EXPECT_EQ(blue.area, 77u);
  EXPECT_DOUBLE_EQ(blue.cx, 105.0);
  EXPECT_DOUBLE_EQ(blue.cy, 8.0);
  const Region& red = regions[1];
  EXPECT_EQ(red.label, 1);
  EXPECT_EQ(red.area, 1200u);
  EXPECT_DOUBLE_EQ(red.cx, 24.5);
  EXPECT_DOUBLE_EQ(red.cy, 39.5);
  EXPECT_EQ(red.left, 10);
  EXPECT_EQ(red.right, 39);
  EXPECT_EQ(red.top, 20);
  EXPECT_EQ(red.bottom, 59);
  EXPECT_NEAR(red.angle, M_PI / 2, 1e-12);  // taller than wide
}

class SimulatedScene : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = loadSceneConfig(sourcePath("config/scene_default.yaml"));
    table_ = std::make_unique<ColorTable>(loadColorClasses(sourcePath("config/colors.yaml")));
  }
  SceneConfig scene_;
  std::unique_ptr<ColorTable> table_;
};

TEST_F(SimulatedScene, NoiseFreeBlobsEqualTheRenderedMasksExactly) {
  scene_.noise_sigma = 0;
  scene_.blur_sigma_px = 0;
  scene_.antialias = false;  // hard edges: the image's pixels are exactly the label masks
  const SceneSimulator simulator(scene_);
  Segmenter segmenter;
  std::vector<Region> regions;
  for (int frame = 0; frame < 300; frame += 7) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    segmenter.segment(f.image, PixelFormat::BGR8, *table_, &regions);
    const std::vector<Region> truth = test::truthRegions(f, *table_);
    ASSERT_GE(truth.size(), 8u) << "the default scene should show most of its 10 boxes";
    ASSERT_EQ(regions.size(), truth.size()) << "frame " << frame << ": no blob may cover ground or sky";
    for (const Region& t : truth) {
      const auto r = std::find_if(regions.begin(), regions.end(), [&](const Region& r) {
        return r.label == t.label && r.left == t.left && r.top == t.top;
      });
      ASSERT_NE(r, regions.end()) << "frame " << frame << " class " << t.label << " at " << t.cx << "," << t.cy;
      EXPECT_EQ(r->area, t.area);
      EXPECT_NEAR(r->cx, t.cx, 1e-9);
      EXPECT_NEAR(r->cy, t.cy, 1e-9);
      EXPECT_EQ(r->right, t.right);
      EXPECT_EQ(r->bottom, t.bottom);
    }
  }
}

TEST_F(SimulatedScene, CentroidErrorBelowOnePixelWithBlurAndSensorNoise) {
  scene_.noise_sigma = 3.0;
  scene_.blur_sigma_px = 1.0;  // mixed colours along every edge: thresholds decide the boundary
  const SceneSimulator simulator(scene_);
  Segmenter segmenter;
  std::vector<Region> regions;
  double worst_clear = 0, worst_adjacent = 0;
  int clear = 0, adjacent = 0;
  for (int frame = 0; frame < 300; frame += 5) {
    const SimFrame f = simulator.render(frame, frame / 30.0);
    segmenter.segment(f.image, PixelFormat::BGR8, *table_, &regions);
    for (const BoxTruth& box : test::isolatedBoxes(f, *table_)) {
      if (box.area < 100) continue;
      const Region* r = regionOfBox(regions, *table_, box, 5.0);
      ASSERT_NE(r, nullptr) << box.name << " frame " << frame;
      const double error = std::hypot(r->cx - box.cx, r->cy - box.cy);
      // Surrounded by ground or sky the blob is the box to within a pixel; next to another box
      // the blurred two-colour edge belongs to neither class and pulls the centroid a little.
      if (box.touches_other_box) {
        worst_adjacent = std::max(worst_adjacent, error);
        ++adjacent;
      } else {
        worst_clear = std::max(worst_clear, error);
        ++clear;
      }
      // Blurred edge pixels are mixtures the class may reject: at most about one pixel of
      // boundary all round is lost or gained.
      const double perimeter = 2.0 * ((box.right - box.left + 1) + (box.bottom - box.top + 1));
      EXPECT_NEAR(r->area, box.area, perimeter) << box.name;
    }
  }
  EXPECT_GT(clear, 100);
  EXPECT_LT(worst_clear, 1.0);
  EXPECT_LT(worst_adjacent, 2.0);
  std::printf("[ centroid ] blur 1 px, noise sigma 3: worst error %.3f px over %d clear boxes, "
              "%.3f px over %d boxes next to another box\n", worst_clear, clear, worst_adjacent, adjacent);
}

TEST_F(SimulatedScene, Yuv422FrameGivesTheSameBlobs) {
  scene_.noise_sigma = 0;
  scene_.blur_sigma_px = 0;
  scene_.antialias = false;
  const SimFrame f = SceneSimulator(scene_).render(0, 0.0);
  Segmenter segmenter;
  std::vector<Region> from_bgr, from_uyvy;
  segmenter.segment(f.image, PixelFormat::BGR8, *table_, &from_bgr);
  segmenter.segment(bgrToUyvy(f.image), PixelFormat::UYVY, *table_, &from_uyvy);
  // 4:2:2 shares chroma between pixel pairs: boundary pixels may change class and a thin
  // fringe (red next to blue reads magenta) may form a small extra blob, as on real cameras.
  for (const Region& b : from_bgr) {
    const auto u = std::find_if(from_uyvy.begin(), from_uyvy.end(), [&](const Region& r) {
      return r.label == b.label && std::hypot(r.cx - b.cx, r.cy - b.cy) < 1.0;
    });
    ASSERT_NE(u, from_uyvy.end()) << "class " << b.label << " at " << b.cx << "," << b.cy;
    EXPECT_NEAR(u->area, b.area, 0.05 * b.area);
  }
  size_t large = 0;
  for (const Region& u : from_uyvy) large += u.area >= 100;
  EXPECT_EQ(large, from_bgr.size());
}

TEST_F(SimulatedScene, FourConnectivityNeverMergesMoreThanEight) {
  const SimFrame f = SceneSimulator(scene_).render(5, 5 / 30.0);
  Segmenter segmenter(SegmenterOptions{Connectivity::Four, 1});
  std::vector<Region> four, eight;
  segmenter.segment(f.image, PixelFormat::BGR8, *table_, &four);
  segmenter.setOptions(SegmenterOptions{Connectivity::Eight, 1});
  segmenter.segment(f.image, PixelFormat::BGR8, *table_, &eight);
  EXPECT_GE(four.size(), eight.size());
}

// Heavy sensor noise on a UYVY frame: with flip_filter_px 2 (4:2:2 flips come in pixel pairs)
// every box is still its blob, larger than without the filter (the holes filled), while the
// runs and the specks the noise made mostly go.
TEST_F(SimulatedScene, FlipFilterKeepsTheBoxesAndDropsTheNoise) {
  scene_.noise_sigma = 40;
  const SimFrame f = SceneSimulator(scene_).render(0, 0.0);
  const cv::Mat uyvy = bgrToUyvy(f.image);
  SegmenterOptions filter;
  filter.flip_filter_px = 2;
  Segmenter plain, filtered(filter);
  std::vector<Region> plain_regions, regions;
  plain.segment(uyvy, PixelFormat::UYVY, *table_, &plain_regions);
  filtered.segment(uyvy, PixelFormat::UYVY, *table_, &regions);
  auto total = [](const std::vector<uint32_t>& counts) { return std::accumulate(counts.begin(), counts.end(), 0u); };
  std::printf("[ flip filter ] noise sigma 40, UYVY: runs %zu -> %zu, regions of any size %u -> %u\n",
              plain.runs().size(), filtered.runs().size(), total(plain.regionCounts()), total(filtered.regionCounts()));
  EXPECT_LT(filtered.runs().size() * 2, plain.runs().size());
  EXPECT_LT(total(filtered.regionCounts()) * 2, total(plain.regionCounts()));
  int boxes = 0;
  for (const BoxTruth& box : test::isolatedBoxes(f, *table_)) {
    // Solid boxes only: a part at most two pixels wide (a thin post) is what the filter removes.
    const double bounding = (box.right - box.left + 1.0) * (box.bottom - box.top + 1.0);
    if (box.area < 400 || box.area < 0.7 * bounding) continue;
    const Region* r = regionOfBox(regions, *table_, box, 2.0);
    const Region* unfiltered = regionOfBox(plain_regions, *table_, box, 2.0);
    ASSERT_NE(r, nullptr) << box.name;
    ASSERT_NE(unfiltered, nullptr) << box.name;
    // Noise this strong takes pixels out of the class; the filter gives the isolated ones back
    // and the blob grows no more than a pixel of boundary all round.
    const double perimeter = 2.0 * ((box.right - box.left + 1) + (box.bottom - box.top + 1));
    EXPECT_GT(r->area, unfiltered->area) << box.name;
    EXPECT_LE(r->area, box.area + perimeter) << box.name;
    ++boxes;
  }
  EXPECT_GT(boxes, 3);
}

TEST(Segmenter, BadImagesThrowWithTheReason) {
  const ColorTable table({makeClass("a", ColorSpace::YUV, {{0, 0, 0}}, {{255, 255, 255}})});
  Segmenter segmenter;
  std::vector<Region> regions;
  EXPECT_THROW(segmenter.segment(cv::Mat(), PixelFormat::BGR8, table, &regions), std::invalid_argument);
  EXPECT_THROW(segmenter.segment(cv::Mat(3, 3, CV_8UC3), PixelFormat::MONO8, table, &regions),
               std::invalid_argument);
  EXPECT_THROW(segmenter.segment(cv::Mat(3, 3, CV_8UC2), PixelFormat::UYVY, table, &regions),
               std::invalid_argument);
  // Tiny images work.
  segmenter.segment(cv::Mat(1, 1, CV_8UC3, cv::Scalar(1, 2, 3)), PixelFormat::BGR8, table, &regions);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].area, 1u);
}

}  // namespace
}  // namespace rle_vision
