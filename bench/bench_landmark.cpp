// Landmark benchmark (issue 3): our 5x5 Sobel and RLE Hough + horizon against OpenCV on the
// same 640x480 frames, one thread, in one run: HoughLinesP on our edge image, and the line
// detectors from the colour frame (FastLineDetector, LSD); line recall and precision of each
// against the simulator's exact edges; the paper's sample-pair comparison (RLE per object vs global).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/fast_line_detector.hpp>

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

// Segments of at least min_length px (our lines' minimum: the peers' shorter ones are not
// counted for or against them).
template <typename Vec4>
std::vector<LineOut> toLines(const std::vector<Vec4>& segments, double min_length = 0) {
  std::vector<LineOut> out;
  for (const Vec4& s : segments) {
    if (std::hypot(s[2] - s[0], s[3] - s[1]) < min_length) continue;
    out.push_back({lineThroughPoints(s[0], s[1], s[2], s[3]), double(s[0]), double(s[1]), double(s[2]), double(s[3])});
  }
  return out;
}

// A peer's time and how it compares with ours, whichever is faster.
void printPeer(const char* name, double peer_ms, double ours_ms) {
  if (peer_ms >= ours_ms) {
    std::printf("  %-46s %8.3f ms   (ours %.1fx faster)\n", name, peer_ms, peer_ms / ours_ms);
  } else {
    std::printf("  %-46s %8.3f ms   (%.1fx faster than ours)\n", name, peer_ms, ours_ms / peer_ms);
  }
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Real frames (no ground truth for their lines: time only), each method from the colour image:
// every 10th frame listed in DIR/label.csv (images in DIR/images/ or DIR/); medians over the
// frames of per-frame medians, as on the simulator. make eval has the accuracy on all of them.
std::vector<cv::Mat> loadRealFrames(const std::string& dir) {
  std::vector<cv::Mat> frames;
  std::ifstream labels(dir + "/label.csv");
  std::string line;
  std::getline(labels, line);  // header
  for (int i = 0; std::getline(labels, line); ++i) {
    if (i % 10 != 0) continue;
    const std::string file = line.substr(0, line.find(','));
    cv::Mat image = cv::imread(dir + "/images/" + file, cv::IMREAD_COLOR);
    if (image.empty()) image = cv::imread(dir + "/" + file, cv::IMREAD_COLOR);
    if (!image.empty()) frames.push_back(image);
  }
  return frames;
}

std::vector<std::pair<std::string, double>> benchRealFrames(const std::string& dir) {
  const std::vector<cv::Mat> frames = loadRealFrames(dir);
  if (frames.empty()) {
    std::printf("\nreal frames: none readable in %s (skipped)\n", dir.c_str());
    return {};
  }
  LandmarkDetector detector;
  LandmarkResult result;
  const LandmarkOptions options;
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  cv::Mat grey, blurred, canny;
  std::vector<cv::Vec4f> segments;
  std::vector<cv::Vec4i> int_segments;
  std::vector<double> ours_ms, fld_ms, lsd_ms, houghp_ms;
  for (const cv::Mat& image : frames) {
    ours_ms.push_back(bench::medianMs([&] { detector.detectInImage(image, options, &result); }, 15, 2));
    fld_ms.push_back(bench::medianMs([&] {
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      fld->detect(grey, segments);
    }, 15, 2));
    lsd_ms.push_back(bench::medianMs([&] {
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      lsd->detect(grey, segments);
    }, 3, 1));
    houghp_ms.push_back(bench::medianMs([&] {
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      cv::GaussianBlur(grey, blurred, cv::Size(5, 5), 1.5);
      cv::Canny(blurred, canny, 30, 90);
      cv::HoughLinesP(canny, int_segments, 1, CV_PI / 180, 30, 30, 8);
    }, 5, 1));
  }
  const double ours = median(ours_ms), fld_time = median(fld_ms), lsd_time = median(lsd_ms), houghp = median(houghp_ms);
  std::printf("\nreal frames: %zu of %s (every 10th labelled, %dx%d), time only (accuracy: make eval)\n", frames.size(),
              dir.c_str(), frames[0].cols, frames[0].rows);
  std::printf("  %-46s %8.3f ms   (frames: %.3f to %.3f ms)\n", "ours: Sobel + RLE Hough + horizon", ours,
              *std::min_element(ours_ms.begin(), ours_ms.end()), *std::max_element(ours_ms.begin(), ours_ms.end()));
  printPeer("cvtColor + FastLineDetector", fld_time, ours);
  printPeer("cvtColor + LSD", lsd_time, ours);
  printPeer("cvtColor + Gauss + Canny + HoughLinesP", houghp, ours);
  return {{"real_frames", double(frames.size())},
          {"real_frame_ms", ours},
          {"real_frame_fld_ms", fld_time},
          {"real_frame_lsd_ms", lsd_time},
          {"real_frame_houghp_ms", houghp}};
}

}  // namespace

// rle_vision_bench_landmark [SOURCE_DIR [JSON [REAL_FRAMES_DIR]]]
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
  std::vector<double> votes_only_ms, no_ridge_ms, paper_pairs_ms, fld_ms, lsd_ms;
  MatchScore ours, opencv, no_ridge, paper_pairs, fld_score, lsd_score;
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  cv::Mat grey;
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
    // The line detectors from the colour frame, as ours (grey conversion included), defaults.
    std::vector<cv::Vec4f> fld_segments, lsd_segments;
    fld_ms.push_back(bench::medianMs([&] {
      cv::cvtColor(frame.image, grey, cv::COLOR_BGR2GRAY);
      fld->detect(grey, fld_segments);
    }, 5, 1));
    lsd_ms.push_back(bench::medianMs([&] {
      cv::cvtColor(frame.image, grey, cv::COLOR_BGR2GRAY);
      lsd->detect(grey, lsd_segments);
    }, 3, 1));

    // Recall over the clear edges (contrast >= 30) of the minimum length; a detection is
    // correct along any visible edge (faint ones too, and shorter ones).
    std::vector<Segment> truth, any_truth;
    for (const EdgeTruth& e : frame.edges) {
      if (std::hypot(e.x2 - e.x1, e.y2 - e.y1) >= options.hough.min_line_length_px) truth.push_back({e.x1, e.y1, e.x2, e.y2});
    }
    for (const EdgeTruth& e : frame.faint_edges) {
      if (std::hypot(e.x2 - e.x1, e.y2 - e.y1) >= 10) any_truth.push_back({e.x1, e.y1, e.x2, e.y2});
    }
    // Recall / precision within 2 deg and 2 px at the truth segment (the segments' own
    // accuracy, without the intercept's extrapolation).
    ours += scoreSegments(result.lines, truth, any_truth, 2.0, 2.0);
    opencv += scoreSegments(toLines(segments), truth, any_truth, 2.0, 2.0);
    fld_score += scoreSegments(toLines(fld_segments, options.hough.min_line_length_px), truth, any_truth, 2.0, 2.0);
    lsd_score += scoreSegments(toLines(lsd_segments, options.hough.min_line_length_px), truth, any_truth, 2.0, 2.0);
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
  const double fld_time = median(fld_ms), lsd_time = median(lsd_ms);
  std::printf("  %-46s %8.3f ms   (docs/DESIGN.md target <= 3)\n", "landmark total: Sobel + RLE Hough + horizon", total);
  printPeer("cvtColor + FastLineDetector (defaults)", fld_time, total);
  printPeer("cvtColor + LSD (LSD_REFINE_STD)", lsd_time, total);
  std::printf("  %-46s %8.3f ms\n", "RLE Hough + horizon on the edge image", hough);
  std::printf("  %-46s %8.3f ms\n", "  of which: RLE into edge objects", objects);
  std::printf("  %-46s %8.3f ms\n", "  of which: the Hough on the edge objects", hough_only);
  std::printf("  %-46s %8.3f ms   (ours %.1fx faster in all, %.1fx the Hough alone)\n", "cv::HoughLinesP on the same edge image",
              houghp, houghp / hough, houghp / hough_only);
  std::printf("  %-46s %8.3f ms\n", "cv::HoughLines on the same edge image", houghs);
  std::printf("  line recall / precision, ours: %.3f / %.3f  (%d truth edges >= 30 px)\n", ours.recall(), ours.precision(), ours.truths);
  std::printf("  line recall / precision, HoughLinesP: %.3f / %.3f\n", opencv.recall(), opencv.precision());
  std::printf("  line recall / precision, FastLineDetector: %.3f / %.3f (its segments >= %.0f px)\n", fld_score.recall(),
              fld_score.precision(), options.hough.min_line_length_px);
  std::printf("  line recall / precision, LSD: %.3f / %.3f (the same)\n", lsd_score.recall(), lsd_score.precision());
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
  std::vector<std::pair<std::string, double>> real;
  if (argc > 3) real = benchRealFrames(argv[3]);
  std::vector<std::pair<std::string, double>> values = {{"sobel_ms", sobel},
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
                               {"fld_ms", fld_time},
                               {"fld_recall", fld_score.recall()},
                               {"fld_precision", fld_score.precision()},
                               {"lsd_ms", lsd_time},
                               {"lsd_recall", lsd_score.recall()},
                               {"lsd_precision", lsd_score.precision()},
                               {"sample_pairs_rle", double(pairs_rle) / kFrames},
                               {"sample_pairs_global", double(pairs_global) / kFrames},
                               {"hough_votes_only_ms", votes_only},
                               {"hough_no_ridge_ms", no_ridge_hough},
                               {"recall_no_ridge", no_ridge.recall()},
                               {"hough_margin1_ms", paper_hough},
                               {"recall_margin1", paper_pairs.recall()},
                               {"horizon_err_deg_median", horizon_err.empty() ? -1.0 : median(horizon_err)}};
  values.insert(values.end(), real.begin(), real.end());
  bench::writeJson(json_path, values);
  std::printf("wrote %s\n", json_path.c_str());
  return 0;
}
