// Tracker benchmark (issue 2): our RLE tracker core against OpenCV doing the same job and a
// memcpy of the frame, on the same 640x480 simulator frame, one thread, in one run.
#include <cstdio>
#include <cstring>

#include <opencv2/core.hpp>

#include "benchmark_frame.h"
#include "harness.h"
#include "opencv_pipeline.h"
#include "rle_vision/blob_tracker.h"
#include "rle_vision/color_convert.h"
#include "rle_vision/segmenter.h"

using namespace rle_vision;

int main(int argc, char** argv) {
  const std::string source_dir = argc > 1 ? argv[1] : RLE_VISION_SOURCE_DIR;
  const std::string json_path = argc > 2 ? argv[2] : source_dir + "/bench/results/tracker.json";
  bench::pinToOneCpu();
  cv::setNumThreads(1);

  const SimFrame frame = benchmarkFrame(source_dir);
  const std::vector<ColorClass> classes = benchmarkClasses(source_dir);
  const ColorTable table(classes);
  const cv::Mat uyvy = bgrToUyvy(frame.image);

  Segmenter segmenter;
  BlobTracker tracker;
  std::vector<Region> regions;
  std::vector<TrackedBlob> blobs;
  double stamp = 0;
  auto track = [&](const cv::Mat& image, PixelFormat format) {
    segmenter.segment(image, format, table, &regions);
    tracker.update(regions, stamp += 1.0 / 30, &blobs);
    bench::keep(blobs);
  };
  const double tracker_ms = bench::medianMs([&] { track(frame.image, PixelFormat::BGR8); });
  const double tracker_yuv422_ms = bench::medianMs([&] { track(uyvy, PixelFormat::UYVY); });

  OpenCvPipeline opencv(classes);
  std::vector<OpenCvBlob> opencv_blobs;
  const double opencv_ms = bench::medianMs([&] {
    opencv.run(frame.image, &opencv_blobs);
    bench::keep(opencv_blobs);
  }, 100, 10);

  cv::Mat copy(frame.image.size(), frame.image.type());
  const size_t bytes = frame.image.total() * frame.image.elemSize();
  const double memcpy_ms = bench::medianMs([&] {
    std::memcpy(copy.data, frame.image.data, bytes);
    bench::keep(copy.data[bytes / 2]);
  });

  const double speedup = opencv_ms / tracker_ms;
  const double ratio_to_memcpy = tracker_ms / memcpy_ms;
  std::printf("rle_vision tracker benchmark: %dx%d bgr8, %zu classes, %zu blobs (config/scene_default.yaml, frame 0)\n",
              frame.image.cols, frame.image.rows, classes.size(), regions.size());
  std::printf("median of timed runs, one thread pinned to one CPU\n");
  std::printf("  %-44s %8.3f ms   (target <= 0.5)\n", "rle_vision tracker core, bgr8", tracker_ms);
  std::printf("  %-44s %8.3f ms   (CMVision on UYVY: ~0.43 ms, DESIGN.md)\n", "rle_vision tracker core, yuv422 (UYVY)", tracker_yuv422_ms);
  std::printf("  %-44s %8.3f ms   (%zu blobs)\n", "OpenCV cvtColor + inRange + CC per class", opencv_ms, opencv_blobs.size());
  std::printf("  %-44s %8.3f ms\n", "memcpy of the frame", memcpy_ms);
  std::printf("  %-44s %8.1f x    (target >= 10)\n", "speedup vs OpenCV", speedup);
  std::printf("  %-44s %8.1f x    (target <= 25)\n", "ratio to memcpy", ratio_to_memcpy);
  bench::writeJson(json_path, {{"tracker_ms", tracker_ms},
                               {"tracker_yuv422_ms", tracker_yuv422_ms},
                               {"opencv_ms", opencv_ms},
                               {"memcpy_ms", memcpy_ms},
                               {"speedup_vs_opencv", speedup},
                               {"ratio_to_memcpy", ratio_to_memcpy}});
  std::printf("wrote %s\n", json_path.c_str());
  return 0;
}
