// Tracker benchmark (issue 2): our RLE tracker core against OpenCV doing the same job and a
// memcpy of the frame, on the same 640x480 simulator frame, one thread, in one run.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <thread>

#include <pthread.h>

#include <opencv2/core.hpp>

#include "eval/benchmark_frame.h"
#include "harness.h"
#include "verifier_timing.h"
#include "eval/opencv_pipeline.h"
#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/learning/color_calibration.h"
#include "rle_vision/color/color_convert.h"
#include "rle_vision/tracking/color_tracker.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/color/shared_color_table.h"
#include "rle_vision/io/yolo_labels.h"

#include <opencv2/imgcodecs.hpp>

using namespace rle_vision;

namespace {

// Segment + tracker on one frame, as bgr8 and as yuv422 (UYVY), and OpenCV's pipeline on it.
struct FrameTimes {
  double bgr_ms = 0, uyvy_ms = 0, opencv_ms = 0;
  size_t runs_bgr = 0, runs_uyvy = 0, regions_bgr = 0, regions_uyvy = 0, opencv_blobs = 0;
};

FrameTimes timeFrame(const cv::Mat& bgr, const std::vector<ColorClass>& classes) {
  const ColorTable table(classes);
  const cv::Mat uyvy = bgrToUyvy(bgr);
  Segmenter segmenter;
  BlobTracker tracker;
  std::vector<Region> regions;
  std::vector<TrackedBlob> blobs;
  double stamp = 0;
  FrameTimes t;
  auto track = [&](const cv::Mat& image, PixelFormat format) {
    segmenter.segment(image, format, table, &regions);
    tracker.update(regions, stamp += 1.0 / 30, &blobs);
    bench::keep(blobs);
  };
  t.bgr_ms = bench::medianMs([&] { track(bgr, PixelFormat::BGR8); });
  t.runs_bgr = segmenter.runs().size(), t.regions_bgr = regions.size();
  t.uyvy_ms = bench::medianMs([&] { track(uyvy, PixelFormat::UYVY); });
  t.runs_uyvy = segmenter.runs().size(), t.regions_uyvy = regions.size();
  OpenCvPipeline opencv(classes);
  std::vector<OpenCvBlob> opencv_blobs;
  t.opencv_ms = bench::medianMs([&] {
    opencv.run(bgr, &opencv_blobs);
    bench::keep(opencv_blobs);
  }, 100, 10);
  t.opencv_blobs = opencv_blobs.size();
  return t;
}

void printFrame(const char* name, const FrameTimes& t) {
  std::printf("  %-44s %8.3f ms   (%zu runs, %zu regions)\n", (std::string(name) + ", bgr8").c_str(), t.bgr_ms, t.runs_bgr,
              t.regions_bgr);
  std::printf("  %-44s %8.3f ms   (%zu runs, %zu regions)\n", (std::string(name) + ", yuv422 (UYVY)").c_str(), t.uyvy_ms,
              t.runs_uyvy, t.regions_uyvy);
  std::printf("  %-44s %8.3f ms\n", (std::string(name) + ", OpenCV pipeline").c_str(), t.opencv_ms);
}

// The segmenter options that change labels for cheaper noisy frames (issue 32), each on its
// path, measured beside the defaults: `key` names them in tracker.json.
struct NoiseOption {
  const char* key;
  PixelFormat format;
  SegmenterOptions options;

  // The frame as this option's path takes it.
  const cv::Mat& frame(const cv::Mat& bgr, const cv::Mat& uyvy) const { return format == PixelFormat::UYVY ? uyvy : bgr; }
};

std::vector<NoiseOption> noiseOptions() {
  SegmenterOptions pair_chroma, flip_filter, both;
  pair_chroma.bgr_pair_chroma = true;
  flip_filter.flip_filter_px = 2;  // 4:2:2 flips come in pixel pairs
  both.bgr_pair_chroma = true;
  both.flip_filter_px = 2;
  return {{"pair_chroma", PixelFormat::BGR8, pair_chroma},
          {"flip_filter_yuv422", PixelFormat::UYVY, flip_filter},
          {"pair_chroma_flip_filter", PixelFormat::BGR8, both}};
}

// A bad frame's cost (issue 18), with CMVision's thresholds (config/colors.txt: every class
// down to 1 px, so every speck is a region): segmentation alone (every region built, as
// CMVision builds them), what the Tracker nodelet runs (ColorTracker: regions under the
// tracking size counted, not built; at most max_regions_per_class tracked), and the tracker
// made to track every region (min_track_area_px 1, no limit), which shows the association's
// cost growing with the regions, not their square.
struct BoundedTimes {
  double segment_bgr_ms = 0, segment_uyvy_ms = 0, tracked_bgr_ms = 0, tracked_uyvy_ms = 0;
  double every_region_bgr_ms = 0, every_region_uyvy_ms = 0;
  size_t regions_bgr = 0, regions_uyvy = 0, blobs_bgr = 0, blobs_uyvy = 0;
  size_t runs_bgr = 0, runs_uyvy = 0;
  std::vector<size_t> option_runs;  // per noiseOptions()
};

// Segment + tracker on one frame, median ms: a fresh tracker, as the node keeps one per stream.
double trackedMs(const cv::Mat& image, PixelFormat format, const ColorTable& table, const SegmenterOptions& options,
                 size_t* blobs_out = nullptr) {
  ColorTracker tracker(options);
  std::vector<TrackedBlob> blobs;
  double stamp = 0;
  const double ms = bench::medianMs([&] {
    tracker.process(image, format, table, stamp += 1.0 / 30, &blobs);
    bench::keep(blobs);
  });
  if (blobs_out) *blobs_out = blobs.size();
  return ms;
}

// The runs the segmenter cuts `image` into.
size_t runCount(const cv::Mat& image, PixelFormat format, const ColorTable& table, const SegmenterOptions& options) {
  Segmenter segmenter(options);
  std::vector<Region> regions;
  segmenter.segment(image, format, table, &regions);
  return segmenter.runs().size();
}

BoundedTimes timeBounded(const cv::Mat& bgr, const std::vector<ColorClass>& classes) {
  const ColorTable table(classes);
  const cv::Mat uyvy = bgrToUyvy(bgr);
  BoundedTimes t;
  for (const bool is_uyvy : {false, true}) {
    const cv::Mat& image = is_uyvy ? uyvy : bgr;
    const PixelFormat format = is_uyvy ? PixelFormat::UYVY : PixelFormat::BGR8;
    Segmenter segmenter;
    std::vector<Region> regions;
    (is_uyvy ? t.segment_uyvy_ms : t.segment_bgr_ms) = bench::medianMs([&] {
      segmenter.segment(image, format, table, &regions);
      bench::keep(regions);
    });
    (is_uyvy ? t.regions_uyvy : t.regions_bgr) = regions.size();
    (is_uyvy ? t.runs_uyvy : t.runs_bgr) = segmenter.runs().size();
    (is_uyvy ? t.tracked_uyvy_ms : t.tracked_bgr_ms) =
        trackedMs(image, format, table, SegmenterOptions(), is_uyvy ? &t.blobs_uyvy : &t.blobs_bgr);
    TrackerOptions every_region;
    every_region.limits.min_track_area_px = 1;
    every_region.limits.max_regions_per_class = UINT32_MAX;
    ColorTracker unbounded(SegmenterOptions(), every_region);
    std::vector<TrackedBlob> blobs;
    double stamp = 0;
    (is_uyvy ? t.every_region_uyvy_ms : t.every_region_bgr_ms) = bench::medianMs([&] {
      unbounded.process(image, format, table, stamp += 1.0 / 30, &blobs);
      bench::keep(blobs);
    }, 40, 5);
  }
  for (const NoiseOption& option : noiseOptions()) {
    const cv::Mat& image = option.frame(bgr, uyvy);
    t.option_runs.push_back(runCount(image, option.format, table, option.options));
  }
  return t;
}

void printBounded(const char* name, const BoundedTimes& t) {
  std::printf("  %s, colors.txt: %zu regions bgr8, %zu yuv422\n", name, t.regions_bgr, t.regions_uyvy);
  std::printf("    %-42s %8.3f ms bgr8 %8.3f ms yuv422\n", "segment only (every region built)", t.segment_bgr_ms,
              t.segment_uyvy_ms);
  std::printf("    %-42s %8.3f ms bgr8 %8.3f ms yuv422   (%zu / %zu blobs)\n", "segment + tracker (the Tracker nodelet)",
              t.tracked_bgr_ms, t.tracked_uyvy_ms, t.blobs_bgr, t.blobs_uyvy);
  std::printf("    %-42s %8.3f ms bgr8 %8.3f ms yuv422\n", "segment + tracking every region", t.every_region_bgr_ms,
              t.every_region_uyvy_ms);
}

// The bench frame with sensor noise of `sigma` (8-bit units per channel) instead of its own.
cv::Mat noisyBenchmarkFrame(const std::string& source_dir, double sigma) {
  SceneConfig config = loadSceneConfig(source_dir + "/config/scene_default.yaml");
  config.noise_sigma = sigma;
  return SceneSimulator(config).render(0, 0.0).image;
}

// A real frame and a class calibrated on its folder's YOLO labels (class 0), as make eval
// does; false when the folder has no labelled boxes or the calibration fails.
bool realFrame(const std::string& folder, cv::Mat* frame, std::vector<ColorClass>* classes) {
  try {
    std::vector<CalibrationExample> examples;
    size_t boxes = 0;
    for (const std::string& path : imagesInFolder(folder)) {
      examples.push_back(readYoloExample(path, 0));
      boxes += examples.back().boxes.size();
    }
    if (boxes == 0) return false;
    *frame = examples.front().bgr;
    *classes = {calibrateColorClass(examples, "ball").color_class};
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "no real frame from %s: %s\n", folder.c_str(), e.what());
    return false;
  }
}

// Segment + tracker on each case's frames, a fresh tracker each (the node keeps one per stream),
// the cases timed in turns, each cycling through its frames: median ms per case.
std::vector<double> trackedMsInTurns(const std::vector<std::vector<cv::Mat>>& cases, PixelFormat format,
                                     const ColorTable& table, const SegmenterOptions& options) {
  std::vector<std::unique_ptr<ColorTracker>> trackers;
  std::vector<std::vector<TrackedBlob>> blobs(cases.size());
  std::vector<double> stamps(cases.size(), 0.0);
  std::vector<size_t> next(cases.size(), 0);
  std::vector<std::function<void()>> bodies;
  for (size_t k = 0; k < cases.size(); ++k) {
    trackers.push_back(std::make_unique<ColorTracker>(options));
    bodies.push_back([&, k] {
      const cv::Mat& image = cases[k][next[k]++ % cases[k].size()];
      trackers[k]->process(image, format, table, stamps[k] += 1.0 / 30, &blobs[k]);
      bench::keep(blobs[k]);
    });
  }
  return bench::medianMsInTurns(bodies);
}

// The noisy frames' cost as ratios to the clean frame's (issue 32: ratios hold on any machine),
// segment + tracker with colors.txt on each path and with each option; the real frames per
// pixel. Each path's frames are timed in turns, so the machine's drift cancels in the ratios.
struct NoiseRatio {
  double clean_ms = 0, noise25 = 0, noise60 = 0, real = 0;
};
struct NoiseRatios {
  NoiseRatio bgr, uyvy;
  std::vector<NoiseRatio> options;  // per noiseOptions()
  int real_frames = 0;
};

// The frames of one case as a path takes them.
std::vector<cv::Mat> asPath(const std::vector<cv::Mat>& bgr_frames, bool uyvy) {
  std::vector<cv::Mat> frames;
  for (const cv::Mat& frame : bgr_frames) frames.push_back(uyvy ? bgrToUyvy(frame) : frame);
  return frames;
}

// `cases`: the clean frames, sigma 25's, sigma 60's, then one case per real frame.
NoiseRatio noiseRatio(const std::vector<std::vector<cv::Mat>>& bgr_cases, bool uyvy, const ColorTable& table,
                      const SegmenterOptions& options) {
  std::vector<std::vector<cv::Mat>> cases;
  for (const std::vector<cv::Mat>& frames : bgr_cases) cases.push_back(asPath(frames, uyvy));
  const std::vector<double> ms = trackedMsInTurns(cases, uyvy ? PixelFormat::UYVY : PixelFormat::BGR8, table, options);
  NoiseRatio r;
  r.clean_ms = ms[0];
  r.noise25 = ms[1] / ms[0];
  r.noise60 = ms[2] / ms[0];
  // Time per pixel against the clean frame's, averaged over the real frames.
  const double clean_ms_per_pixel = ms[0] / static_cast<double>(cases[0][0].total());
  const double real_frames = static_cast<double>(cases.size() - 3);
  for (size_t k = 3; k < cases.size(); ++k) {
    r.real += ms[k] / static_cast<double>(cases[k][0].total()) / clean_ms_per_pixel / real_frames;
  }
  return r;
}

// The bench scene at t = 0 with `sigma` noise (the scene's own when 0), one frame per noise
// field: a camera's noise is new in every frame, and timing one noisy frame over and over lets
// the CPU's branch predictor learn that frame's noise (at sigma 60 the flip filter's path took
// half the time it takes on fresh noise).
std::vector<cv::Mat> noiseFields(const std::string& source_dir, double sigma, int count = 8) {
  SceneConfig config = loadSceneConfig(source_dir + "/config/scene_default.yaml");
  if (sigma > 0) config.noise_sigma = sigma;
  const SceneSimulator simulator(config);
  std::vector<cv::Mat> frames;
  for (int k = 0; k < count; ++k) frames.push_back(simulator.render(static_cast<uint64_t>(k), 0.0).image);
  return frames;
}

NoiseRatios noiseRatios(const std::string& source_dir, const std::vector<cv::Mat>& real_frames,
                        const std::vector<ColorClass>& classes) {
  std::vector<std::vector<cv::Mat>> cases{noiseFields(source_dir, 0), noiseFields(source_dir, 25),
                                          noiseFields(source_dir, 60)};
  for (const cv::Mat& frame : real_frames) cases.push_back({frame});
  const ColorTable table(classes);
  NoiseRatios r;
  r.bgr = noiseRatio(cases, false, table, SegmenterOptions());
  r.uyvy = noiseRatio(cases, true, table, SegmenterOptions());
  for (const NoiseOption& option : noiseOptions()) {
    r.options.push_back(noiseRatio(cases, option.format == PixelFormat::UYVY, table, option.options));
  }
  r.real_frames = static_cast<int>(real_frames.size());
  return r;
}

// Up to `count` frames of a folder (its first images, sorted).
std::vector<cv::Mat> firstFrames(const std::string& folder, size_t count) {
  std::vector<cv::Mat> frames;
  if (folder.empty()) return frames;
  for (const std::string& path : imagesInFolder(folder)) {
    if (frames.size() == count) break;
    cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (!image.empty() && image.cols % 2 == 0) frames.push_back(image);  // UYVY pairs pixels
  }
  return frames;
}

void printNoiseRatios(const NoiseRatios& r) {
  std::printf("  noisy against clean, segment + tracker, colors.txt, each path's frames timed in turns (clean frame: "
              "%.3f ms bgr8, %.3f ms yuv422):\n", r.bgr.clean_ms, r.uyvy.clean_ms);
  std::printf("    %-42s %6.2f x bgr8 %6.2f x yuv422  (targets <= 1.3 x)\n", "noise sigma 25 / clean", r.bgr.noise25,
              r.uyvy.noise25);
  std::printf("    %-42s %6.2f x bgr8 %6.2f x yuv422  (targets <= 3 x)\n", "noise sigma 60 / clean", r.bgr.noise60,
              r.uyvy.noise60);
  if (r.real_frames > 0) {
    std::printf("    %-42s %6.2f x bgr8 %6.2f x yuv422  (%d frames, time per pixel)\n", "real robot frames / clean",
                r.bgr.real, r.uyvy.real, r.real_frames);
  }
  const std::vector<NoiseOption> options = noiseOptions();
  for (size_t k = 0; k < options.size(); ++k) {
    std::printf("    %-42s %6.2f x sigma 25 %6.2f x sigma 60 %6.2f x real  (clean %.3f ms)\n",
                (std::string("with ") + options[k].key).c_str(), r.options[k].noise25, r.options[k].noise60,
                r.options[k].real, r.options[k].clean_ms);
  }
}

// The tracker loop while colour learning replaces the table: an updater thread on the other CPU
// stores another table (ranges nudged) after every frame; the frame path takes a snapshot per
// frame, as the Tracker nodelet does, and never waits. Returns the median frame time.
double timeWithTableSwaps(const cv::Mat& image, const std::vector<ColorClass>& classes, double* swaps_per_frame) {
  Segmenter segmenter;
  BlobTracker tracker;
  std::vector<Region> regions;
  std::vector<TrackedBlob> blobs;
  double stamp = 0;
  SharedColorTable shared;
  shared.store(std::make_shared<const ColorTable>(classes));
  std::atomic<bool> stop{false};
  std::atomic<long> frames_done{0}, swaps{0};
  std::thread updater([&] {
    cpu_set_t other;
    CPU_ZERO(&other);
    CPU_SET(std::thread::hardware_concurrency() > 1 ? 1 : 0, &other);
    pthread_setaffinity_np(pthread_self(), sizeof(other), &other);
    // Three tables with the ranges nudged by -1, 0 and +1, built once here (building one takes
    // longer than a frame; in the Tracker nodelet it happens off the frame path too), then
    // swapped in round robin, one per frame.
    std::vector<std::shared_ptr<const ColorTable>> tables;
    for (int step = -1; step <= 1; ++step) {
      std::vector<ColorClass> nudged = classes;
      for (size_t k = 0; k < nudged.size(); ++k)
        for (int c = 1; c < 3; ++c) {
          nudged[k].min[c] = static_cast<uint8_t>(classes[k].min[c] + (classes[k].min[c] > 0 ? step : 0));
          nudged[k].max[c] = static_cast<uint8_t>(classes[k].max[c] - (classes[k].max[c] < 255 ? step : 0));
        }
      tables.push_back(std::make_shared<const ColorTable>(nudged));
    }
    long last_frame = -1;
    while (!stop.load()) {
      const long frame_now = frames_done.load();
      if (frame_now == last_frame) {  // one swap per frame is enough to prove the point
        std::this_thread::yield();
        continue;
      }
      last_frame = frame_now;
      shared.store(tables[swaps.load() % tables.size()]);
      ++swaps;
    }
  });
  long timed_frames = 0;
  const double ms = bench::medianMs([&] {
    const std::shared_ptr<const ColorTable> snapshot = shared.load();
    segmenter.segment(image, PixelFormat::BGR8, *snapshot, &regions);
    tracker.update(regions, stamp += 1.0 / 30, &blobs);
    bench::keep(blobs);
    ++frames_done;
    ++timed_frames;
  });
  stop = true;
  updater.join();
  *swaps_per_frame = static_cast<double>(swaps.load()) / timed_frames;
  return ms;
}

double memcpyMs(const cv::Mat& image) {
  cv::Mat copy(image.size(), image.type());
  const size_t bytes = image.total() * image.elemSize();
  return bench::medianMs([&] {
    std::memcpy(copy.data, image.data, bytes);
    bench::keep(copy.data[bytes / 2]);
  });
}

using Values = std::vector<std::pair<std::string, double>>;

void addFrame(const std::string& name, const FrameTimes& t, Values* values) {
  values->insert(values->end(), {{"tracker_" + name + "_ms", t.bgr_ms},
                                 {"tracker_" + name + "_yuv422_ms", t.uyvy_ms},
                                 {"opencv_" + name + "_ms", t.opencv_ms}});
}

void addBounded(const std::string& name, const BoundedTimes& t, Values* values) {
  const std::string key = "bounded_" + name + "_";
  values->insert(values->end(), {{key + "segment_ms", t.segment_bgr_ms},
                                 {key + "segment_yuv422_ms", t.segment_uyvy_ms},
                                 {key + "tracker_ms", t.tracked_bgr_ms},
                                 {key + "tracker_yuv422_ms", t.tracked_uyvy_ms},
                                 {key + "every_region_ms", t.every_region_bgr_ms},
                                 {key + "every_region_yuv422_ms", t.every_region_uyvy_ms},
                                 {key + "runs", static_cast<double>(t.runs_bgr)},
                                 {key + "runs_yuv422", static_cast<double>(t.runs_uyvy)},
                                 {key + "regions", static_cast<double>(t.regions_bgr)},
                                 {key + "regions_yuv422", static_cast<double>(t.regions_uyvy)}});
  const std::vector<NoiseOption> options = noiseOptions();
  for (size_t k = 0; k < options.size(); ++k) {
    values->push_back({key + "runs_" + options[k].key, static_cast<double>(t.option_runs[k])});
  }
}

void addNoiseRatio(const std::string& suffix, const NoiseRatio& r, Values* values) {
  values->insert(values->end(), {{"noise25_to_clean_tracker" + suffix + "_ratio", r.noise25},
                                 {"noise60_to_clean_tracker" + suffix + "_ratio", r.noise60},
                                 {"real_to_clean_tracker" + suffix + "_ratio_per_pixel", r.real},
                                 {"noise_ratio_clean_tracker" + suffix + "_ms", r.clean_ms}});
}

void addNoiseRatios(const NoiseRatios& r, Values* values) {
  addNoiseRatio("", r.bgr, values);
  addNoiseRatio("_yuv422", r.uyvy, values);
  const std::vector<NoiseOption> options = noiseOptions();
  for (size_t k = 0; k < options.size(); ++k) addNoiseRatio(std::string("_") + options[k].key, r.options[k], values);
  values->push_back({"real_ratio_frames", static_cast<double>(r.real_frames)});
}

// The clean frame's figures: ours (bgr8, UYVY, with table swaps), OpenCV's, memcpy's.
struct CleanTimes {
  FrameTimes frame;
  double with_updates_ms = 0, swaps_per_frame = 0, memcpy_ms = 0;
};

void printClean(const SimFrame& frame, size_t classes, const CleanTimes& c) {
  std::printf("rle_vision tracker benchmark: %dx%d bgr8, %zu classes, %zu blobs (config/scene_default.yaml, frame 0)\n",
              frame.image.cols, frame.image.rows, classes, c.frame.regions_bgr);
  std::printf("median of timed runs, one thread pinned to one CPU\n");
  std::printf("  %-44s %8.3f ms   (target <= 0.5)\n", "rle_vision tracker core, bgr8", c.frame.bgr_ms);
  std::printf("  %-44s %8.3f ms\n", "rle_vision tracker core, yuv422 (UYVY)",
              c.frame.uyvy_ms);
  std::printf("  %-44s %8.3f ms   (target <= 0.5; %.2f swaps per frame)\n", "rle_vision tracker core, bgr8, table swaps",
              c.with_updates_ms, c.swaps_per_frame);
  std::printf("  %-44s %8.3f ms   (%zu blobs)\n", "OpenCV cvtColor + inRange + CC per class", c.frame.opencv_ms,
              c.frame.opencv_blobs);
  std::printf("  %-44s %8.3f ms\n", "memcpy of the frame", c.memcpy_ms);
  std::printf("  %-44s %8.1f x    (target >= 10)\n", "speedup vs OpenCV", c.frame.opencv_ms / c.frame.bgr_ms);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string source_dir = argc > 1 ? argv[1] : RLE_VISION_SOURCE_DIR;
  const std::string json_path = argc > 2 ? argv[2] : source_dir + "/bench/measured/tracker.json";
  const std::string real_folder = argc > 3 ? argv[3] : "";
  bench::pinToOneCpu();
  cv::setNumThreads(1);

  const SimFrame frame = benchmarkFrame(source_dir);
  const std::vector<ColorClass> classes = benchmarkClasses(source_dir);
  CleanTimes clean;
  clean.frame = timeFrame(frame.image, classes);
  clean.with_updates_ms = timeWithTableSwaps(frame.image, classes, &clean.swaps_per_frame);
  clean.memcpy_ms = memcpyMs(frame.image);

  // Real cameras are noisy: the bench frame with sensor noise sigma 25 and 60, and a real frame.
  const cv::Mat noisy25 = noisyBenchmarkFrame(source_dir, 25), noisy60 = noisyBenchmarkFrame(source_dir, 60);
  const FrameTimes noise25 = timeFrame(noisy25, classes);
  const FrameTimes noise60 = timeFrame(noisy60, classes);
  const std::vector<ColorClass> cmvision_classes = loadColorClasses(source_dir + "/config/colors.txt");
  const BoundedTimes bounded25 = timeBounded(noisy25, cmvision_classes);
  const BoundedTimes bounded60 = timeBounded(noisy60, cmvision_classes);
  const BoundedTimes bounded_clean = timeBounded(frame.image, cmvision_classes);
  const NoiseRatios ratios = noiseRatios(source_dir, firstFrames(real_folder, 3), cmvision_classes);
  cv::Mat real;
  std::vector<ColorClass> real_classes;
  const bool have_real = !real_folder.empty() && realFrame(real_folder, &real, &real_classes);
  const FrameTimes real_times = have_real ? timeFrame(real, real_classes) : FrameTimes();

  const bench::VerifierTimes verifier =
      bench::timeVerifier(frame.image, classes, source_dir + "/config/ball_verifier.yml.gz");

  const double ratio_to_memcpy = clean.frame.bgr_ms / clean.memcpy_ms;
  printClean(frame, classes.size(), clean);
  printFrame("noise sigma 25", noise25);
  std::printf("  %-44s %8s      (target bgr8 <= 0.30 ms)\n", "", "");
  printFrame("noise sigma 60", noise60);
  if (have_real) {
    printFrame((std::to_string(real.cols) + "x" + std::to_string(real.rows) + " real frame").c_str(), real_times);
  }
  std::printf("  %-44s %8.1f x    (target <= 25)\n", "ratio to memcpy", ratio_to_memcpy);
  printBounded("noise sigma 25", bounded25);
  std::printf("    %-42s targets: segment + tracker bgr8 <= 0.5 ms\n", "");
  printBounded("noise sigma 60", bounded60);
  std::printf("    %-42s targets: segment + tracker yuv422 <= 1.6 ms, bgr8 <= 3 ms\n", "");
  printNoiseRatios(ratios);
  std::printf("  verifier (config/ball_verifier.yml.gz), %zu candidates on the 640x480 frame, %zu scored (the cap):\n",
              verifier.candidates, verifier.scored);
  std::printf("    %-42s %8.3f ms\n", "segment + tracker alone", verifier.tracker_ms);
  std::printf("    %-42s %8.3f ms  (%.2f us a candidate; target <= 0.2 ms at 50)\n", "verifier: features and score",
              verifier.verifier_ms, 1e3 * verifier.verifier_ms / std::max<size_t>(1, verifier.scored));
  Values values = {{"tracker_ms", clean.frame.bgr_ms},
                   {"tracker_yuv422_ms", clean.frame.uyvy_ms},
                   {"tracker_ms_with_updates", clean.with_updates_ms},
                   {"table_swaps_per_frame", clean.swaps_per_frame},
                   {"opencv_ms", clean.frame.opencv_ms},
                   {"memcpy_ms", clean.memcpy_ms},
                   {"speedup_vs_opencv", clean.frame.opencv_ms / clean.frame.bgr_ms},
                   {"ratio_to_memcpy", ratio_to_memcpy}};
  addFrame("noise25", noise25, &values);
  addFrame("noise60", noise60, &values);
  addFrame("real", real_times, &values);
  addBounded("noise25", bounded25, &values);
  addBounded("noise60", bounded60, &values);
  addBounded("clean", bounded_clean, &values);
  addNoiseRatios(ratios, &values);
  values.push_back({"verifier_candidates", static_cast<double>(verifier.candidates)});
  values.push_back({"verifier_scored", static_cast<double>(verifier.scored)});
  values.push_back({"verifier_frame_tracker_ms", verifier.tracker_ms});
  values.push_back({"verifier_ms", verifier.verifier_ms});
  bench::writeJson(json_path, values);
  std::printf("wrote %s\n", json_path.c_str());
  return 0;
}
