// Landmark benchmark (issue 3): our 5x5 Sobel and RLE Hough + horizon against OpenCV on the
// same 640x480 frames, one thread, in one run; line recall and precision of each against the
// simulator's exact edges; the paper's sample-pair comparison (RLE per object vs global).
#include <algorithm>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "benchmark_frame.h"
#include "harness.h"
#include "line_matching.h"
#include "rle_vision/landmark_detector.h"

using namespace rle_vision;

namespace {

constexpr int kFrames = 20;  // frames of the walking gait, one every 7 frames (0.23 s)

// OpenCV's 5x5 Sobel doing our job: x and y derivatives of the 3 channels, the largest
// channel magnitude, scaled like ours. Its buffers persist across calls, as ours do (fresh
// multi-megabyte buffers every frame would time page faults, not the filter).
struct OpencvSobelBuffers {
  cv::Mat gx, gy, fx, fy, magnitude, largest;
  std::vector<cv::Mat> channels;
};

void opencvSobel(const cv::Mat& bgr, double gain, OpencvSobelBuffers* b, cv::Mat* edges) {
  cv::Sobel(bgr, b->gx, CV_16S, 1, 0, 5);
  cv::Sobel(bgr, b->gy, CV_16S, 0, 1, 5);
  b->gx.convertTo(b->fx, CV_32F);
  b->gy.convertTo(b->fy, CV_32F);
  cv::magnitude(b->fx.reshape(1), b->fy.reshape(1), b->magnitude);
  cv::split(b->magnitude.reshape(3), b->channels);
  cv::max(b->channels[0], b->channels[1], b->largest);
  cv::max(b->largest, b->channels[2], b->largest);
  b->largest.convertTo(*edges, CV_8U, gain / kSobel5StepGain);
}

struct LineOut {
  ImageLine line;
  double x1, y1, x2, y2;
};

std::vector<LineOut> toLines(const std::vector<cv::Vec4i>& segments) {
  std::vector<LineOut> out;
  for (const cv::Vec4i& s : segments) {
    out.push_back({lineThroughPoints(s[0], s[1], s[2], s[3]), double(s[0]), double(s[1]), double(s[2]), double(s[3])});
  }
  return out;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::string source_dir = argc > 1 ? argv[1] : RLE_VISION_SOURCE_DIR;
  const std::string json_path = argc > 2 ? argv[2] : source_dir + "/bench/results/landmark.json";
  bench::pinToOneCpu();
  cv::setNumThreads(1);

  const SceneSimulator simulator(loadSceneConfig(source_dir + "/config/scene_default.yaml"));
  std::vector<SimFrame> frames;
  for (int i = 0; i < kFrames; ++i) frames.push_back(simulator.render(7 * i, 7 * i / 30.0));

  LandmarkOptions options;
  LandmarkDetector detector;
  Sobel5 sobel5;
  LandmarkResult result;
  EdgeObjectFinder finder;
  RleHough rle_hough;
  std::vector<double> objects_ms, hough_only_ms;
  std::vector<double> sobel_ms, opencv_sobel_ms, opencv_derivatives_ms, total_ms, hough_ms, houghp_ms, houghs_ms, horizon_err;
  std::vector<double> votes_only_ms, no_ridge_ms, paper_pairs_ms;
  MatchScore ours, opencv, no_ridge, paper_pairs;
  uint64_t pairs_rle = 0, pairs_global = 0;
  cv::Mat edges, cv_edges, gx, gy;
  OpencvSobelBuffers cv_buffers;
  for (const SimFrame& frame : frames) {
    sobel_ms.push_back(bench::medianMs([&] { sobel5.edges(frame.image, options.edge_gain, &edges); }, 30, 3));
    opencv_sobel_ms.push_back(bench::medianMs([&] { opencvSobel(frame.image, options.edge_gain, &cv_buffers, &cv_edges); }, 10, 2));
    // cv::Sobel's two derivative passes alone (no magnitude): a lower bound for OpenCV.
    opencv_derivatives_ms.push_back(bench::medianMs([&] {
      cv::Sobel(frame.image, gx, CV_16S, 1, 0, 5);
      cv::Sobel(frame.image, gy, CV_16S, 0, 1, 5);
    }, 10, 2));
    // The whole landmark step, and the Hough + horizon step alone on the same edge image.
    total_ms.push_back(bench::medianMs([&] { detector.detectInImage(frame.image, options, &result); }, 15, 2));
    hough_ms.push_back(bench::medianMs([&] { detector.detectInEdges(edges, options, &result); }, 15, 2));
    // Its two parts: the RLE of the edge image into edge objects, and the Hough on them.
    objects_ms.push_back(bench::medianMs([&] { finder.find(edges, options.objects); }, 15, 2));
    std::vector<DetectedLine> hough_lines;
    HoughStats hough_stats;
    hough_only_ms.push_back(bench::medianMs([&] {
      rle_hough.detect(finder, edges, options.objects.gray_threshold, options.hough, &hough_lines, &hough_stats);
    }, 15, 2));
    // What a 5x speed-up over HoughLinesP has to fit in (README): the first sampling round's
    // votes and seed ordering, no peak refined (no failed peaks allowed ends it there); the Hough refining by least squares on the run pixels instead
    // of the sub-pixel ridge fit; and with the paper's own pair count (eq. 4, margin 1, not 3).
    HoughOptions votes_only = options.hough, paper = options.hough;
    votes_only.max_failed_peaks = 0;
    paper.sampling_margin = 1;
    votes_only_ms.push_back(bench::medianMs([&] {
      rle_hough.detect(finder, edges, options.objects.gray_threshold, votes_only, &hough_lines, &hough_stats);
    }, 15, 2));
    std::vector<DetectedLine> no_ridge_lines, paper_lines;
    no_ridge_ms.push_back(bench::medianMs([&] {
      rle_hough.detectOnRuns(finder, edges.cols, edges.rows, options.hough, &no_ridge_lines, &hough_stats);
    }, 15, 2));
    paper_pairs_ms.push_back(bench::medianMs([&] {
      rle_hough.detect(finder, edges, options.objects.gray_threshold, paper, &paper_lines, &hough_stats);
    }, 15, 2));
    pairs_rle += result.hough.sample_pairs;
    pairs_global += result.hough.global_sample_pairs;
    // OpenCV's Hough on the same edge image, thresholded at our gray threshold.
    cv::Mat binary = edges >= options.objects.gray_threshold;
    std::vector<cv::Vec4i> segments;
    houghp_ms.push_back(bench::medianMs([&] {
      cv::HoughLinesP(binary, segments, 1, CV_PI / 180, 30, options.hough.min_line_length_px, options.hough.max_gap_px);
    }, 5, 1));
    std::vector<cv::Vec2f> standard;
    houghs_ms.push_back(bench::medianMs([&] { cv::HoughLines(binary, standard, 1, CV_PI / 180, 60); }, 5, 1));

    std::vector<Segment> truth, any_truth;
    for (const EdgeTruth& e : frame.edges) {
      const double length = std::hypot(e.x2 - e.x1, e.y2 - e.y1);
      if (length >= options.hough.min_line_length_px) truth.push_back({e.x1, e.y1, e.x2, e.y2});
      if (length >= 10) any_truth.push_back({e.x1, e.y1, e.x2, e.y2});
    }
    // Recall / precision within 2 deg and 2 px at the truth segment (the segments' own
    // accuracy, without the intercept's extrapolation).
    ours += scoreSegments(result.lines, truth, any_truth, 2.0, 2.0);
    opencv += scoreSegments(toLines(segments), truth, any_truth, 2.0, 2.0);
    no_ridge += scoreSegments(no_ridge_lines, truth, any_truth, 2.0, 2.0);
    paper_pairs += scoreSegments(paper_lines, truth, any_truth, 2.0, 2.0);
    if (result.horizon.found && frame.horizon_visible) {
      horizon_err.push_back(lineAngleDifference(result.horizon.line.theta, frame.horizon.theta) * 180 / M_PI);
    }
  }

  const double sobel = median(sobel_ms), cv_sobel = median(opencv_sobel_ms), total = median(total_ms);
  const double cv_derivatives = median(opencv_derivatives_ms);
  const double hough = median(hough_ms), houghp = median(houghp_ms), houghs = median(houghs_ms);
  const double objects = median(objects_ms), hough_only = median(hough_only_ms);
  std::printf("rle_vision landmark benchmark: %d simulator frames 640x480 (config/scene_default.yaml, walking gait)\n", kFrames);
  std::printf("medians over frames of per-frame medians, one thread pinned to one CPU\n");
  std::printf("  %-46s %8.3f ms\n", "our 5x5 Sobel (3 channels, max magnitude)", sobel);
  std::printf("  %-46s %8.3f ms   (ours %.1fx faster)\n", "OpenCV cv::Sobel ksize 5, same job", cv_sobel, cv_sobel / sobel);
  std::printf("  %-46s %8.3f ms   (ours %.1fx faster)\n", "OpenCV cv::Sobel x and y only (no magnitude)", cv_derivatives, cv_derivatives / sobel);
  std::printf("  %-46s %8.3f ms   (target <= 3)\n", "landmark total: Sobel + RLE Hough + horizon", total);
  std::printf("  %-46s %8.3f ms\n", "RLE Hough + horizon on the edge image", hough);
  std::printf("  %-46s %8.3f ms\n", "  of which: RLE into edge objects", objects);
  std::printf("  %-46s %8.3f ms\n", "  of which: the Hough on the edge objects", hough_only);
  std::printf("  %-46s %8.3f ms   (ours %.1fx faster in all, %.1fx the Hough alone)\n", "cv::HoughLinesP on the same edge image",
              houghp, houghp / hough, houghp / hough_only);
  std::printf("  %-46s %8.3f ms\n", "cv::HoughLines on the same edge image", houghs);
  std::printf("  line recall / precision, ours:   %.3f / %.3f  (%d truth edges >= 30 px)\n", ours.recall(), ours.precision(), ours.truths);
  std::printf("  line recall / precision, OpenCV: %.3f / %.3f\n", opencv.recall(), opencv.precision());
  const double votes_only = median(votes_only_ms), no_ridge_hough = median(no_ridge_ms), paper_hough = median(paper_pairs_ms);
  std::printf("  5x HoughLinesP means <= %.3f ms for the RLE and the Hough; of it, before any refinement:\n", houghp / 5);
  std::printf("  %-46s %8.3f ms\n", "  the RLE into edge objects", objects);
  std::printf("  %-46s %8.3f ms\n", "  first sampling round: votes, seeds ordered", votes_only);
  std::printf("  %-46s %8.3f ms   (recall / precision %.3f / %.3f)\n", "the Hough without the sub-pixel ridge fit", no_ridge_hough,
              no_ridge.recall(), no_ridge.precision());
  std::printf("  %-46s %8.3f ms   (recall / precision %.3f / %.3f)\n", "the Hough with eq. 4's pairs at margin 1", paper_hough,
              paper_pairs.recall(), paper_pairs.precision());
  std::printf("  sample pairs per frame: RLE per object %.0f, global random Hough (eq. 4) %.0f\n",
              double(pairs_rle) / kFrames, double(pairs_global) / kFrames);
  std::printf("  horizon angle error, median: %.3f deg over %zu frames\n",
              horizon_err.empty() ? -1.0 : median(horizon_err), horizon_err.size());
  bench::writeJson(json_path, {{"sobel_ms", sobel},
                               {"opencv_sobel_ms", cv_sobel},
                               {"opencv_sobel_derivatives_only_ms", cv_derivatives},
                               {"landmark_total_ms", total},
                               {"hough_ms", hough},
                               {"opencv_houghp_ms", houghp},
                               {"opencv_hough_ms", houghs},
                               {"speedup_vs_houghp", houghp / hough},
                               {"edge_objects_ms", objects},
                               {"hough_only_ms", hough_only},
                               {"speedup_vs_houghp_hough_only", houghp / hough_only},
                               {"recall", ours.recall()},
                               {"precision", ours.precision()},
                               {"opencv_recall", opencv.recall()},
                               {"opencv_precision", opencv.precision()},
                               {"sample_pairs_rle", double(pairs_rle) / kFrames},
                               {"sample_pairs_global", double(pairs_global) / kFrames},
                               {"hough_votes_only_ms", votes_only},
                               {"hough_no_ridge_ms", no_ridge_hough},
                               {"recall_no_ridge", no_ridge.recall()},
                               {"hough_margin1_ms", paper_hough},
                               {"recall_margin1", paper_pairs.recall()},
                               {"horizon_err_deg_median", horizon_err.empty() ? -1.0 : median(horizon_err)}});
  std::printf("wrote %s\n", json_path.c_str());
  return 0;
}
