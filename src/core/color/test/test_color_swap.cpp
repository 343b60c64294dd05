// The tracker swaps colour tables while frames are segmented. Built with ThreadSanitizer:
// any data race fails the test (TSan exits non-zero); each frame must also see one whole table.
#include <atomic>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/segment/segmenter.h"
#include "rle_vision/color/shared_color_table.h"
#include "testing/test_helpers.h"

// Stop at the first race report: the test then writes no result file, which counts as failed.
extern "C" const char* __tsan_default_options() { return "halt_on_error=1"; }

namespace rle_vision {
namespace {

using test::makeClass;

TEST(SharedColorTable, SwapsUnderConcurrentFramesAreRaceFreeAndWhole) {
  cv::Mat image(120, 160, CV_8UC3, cv::Scalar(0, 100, 0));
  for (int i = 0; i < 3; ++i) {
    cv::rectangle(image, cv::Rect(10 + 50 * i, 10, 20, 20), cv::Scalar(0, 0, 250), cv::FILLED);  // red
  }
  for (int i = 0; i < 2; ++i) {
    cv::rectangle(image, cv::Rect(10 + 50 * i, 70, 20, 20), cv::Scalar(250, 0, 0), cv::FILLED);  // blue
  }
  const ColorClass red = makeClass("red", ColorSpace::RGB, {{200, 0, 0}}, {{255, 50, 50}});
  const ColorClass blue = makeClass("blue", ColorSpace::RGB, {{0, 0, 200}}, {{50, 50, 255}});
  // Two classes see 5 blobs, one class sees 2.
  SharedColorTable shared;
  shared.store(std::make_shared<const ColorTable>(std::vector<ColorClass>{red, blue}));

  std::atomic<bool> done{false};
  std::atomic<int> frames{0}, inconsistent{0};
  auto reader = [&] {
    Segmenter segmenter;
    std::vector<Region> regions;
    while (!done.load()) {
      const std::shared_ptr<const ColorTable> table = shared.load();
      segmenter.segment(image, PixelFormat::BGR8, *table, &regions);
      const size_t expected = table->size() == 2 ? 5u : 2u;
      if (regions.size() != expected) ++inconsistent;
      ++frames;
    }
  };
  std::thread reader_a(reader), reader_b(reader);
  for (int i = 0; i < 2000; ++i) {
    // A fresh table each time: the old one is freed while a reader may still hold it.
    if (i % 2) {
      shared.store(std::make_shared<const ColorTable>(std::vector<ColorClass>{red, blue}));
    } else {
      shared.store(std::make_shared<const ColorTable>(std::vector<ColorClass>{blue}));
    }
    if (i % 100 == 0) std::this_thread::yield();
  }
  while (frames.load() < 50) std::this_thread::yield();
  done = true;
  reader_a.join();
  reader_b.join();
  EXPECT_EQ(inconsistent.load(), 0);
  EXPECT_GE(frames.load(), 50);
}

}  // namespace
}  // namespace rle_vision
