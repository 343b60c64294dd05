// Landmark benchmark (issue 3): our 5x5 Sobel and RLE Hough + horizon against OpenCV on the
// same 640x480 frames, one thread, in one run: HoughLinesP on our edge image, and the line
// detectors from the colour frame (FastLineDetector, LSD); line recall and precision of each
// against the simulator's exact edges; the paper's sample-pair comparison (RLE per object vs global).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/fast_line_detector.hpp>

#include "eval/benchmark_frame.h"
#include "harness.h"
#include "eval/line_matching.h"
#include "rle_vision/field/field_detector.h"
#include "rle_vision/io/horizon_model_file.h"
#include "rle_vision/landmark/landmark_detector.h"

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

// Real frames (no ground truth for their lines: time only), each method from the colour image,
// as the nodes run (the landmark with the shipped horizon model): medians over the frames of
// per-frame medians, as on the simulator. make eval has the accuracy on all of them.
// UAV frames: every 10th frame listed in DIR/label.csv (images in DIR/images/ or DIR/).
std::vector<cv::Mat> loadLabelledFrames(const std::string& dir) {
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

// The robot's own kind of frame: every 15th image under DIR (sorted; indoor MSL frames).
std::vector<cv::Mat> loadEveryFifteenth(const std::string& dir) {
  std::vector<std::string> paths;
  if (std::filesystem::is_directory(dir)) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
      if (entry.is_regular_file() && entry.path().extension() == ".jpg") paths.push_back(entry.path().string());
    }
  }
  std::sort(paths.begin(), paths.end());
  std::vector<cv::Mat> frames;
  for (size_t i = 0; i < paths.size(); i += 15) {
    cv::Mat image = cv::imread(paths[i], cv::IMREAD_COLOR);
    if (!image.empty()) frames.push_back(image);
  }
  return frames;
}

using Values = std::vector<std::pair<std::string, double>>;

// Ours (whole and per stage) against the line detectors on `frames`, keys prefixed `key`.
Values benchRealFrames(const std::vector<cv::Mat>& frames, const std::string& key, const std::string& title) {
  if (frames.empty()) {
    std::printf("\n%s: none readable (skipped)\n", title.c_str());
    return {};
  }
  LandmarkDetector detector;
  LandmarkResult result;
  LandmarkOptions options;
  options.horizon.model = horizonModelFromSetting("");
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  cv::Mat grey, blurred, canny;
  std::vector<cv::Vec4f> segments;
  std::vector<cv::Vec4i> int_segments;
  std::vector<double> ours_ms, sobel_ms, objects_ms, hough_ms, horizon_ms, fld_ms, lsd_ms, houghp_ms, field_ms;
  int budget_cut = 0;
  FieldDetector field;  // as in a stream: the colour seeded once, then followed
  FieldResult field_result;
  for (const cv::Mat& image : frames) {
    ours_ms.push_back(bench::medianMs([&] { detector.detectInImage(image, options, &result); }, 9, 2));
    budget_cut += result.hough.budget_exhausted;
    field_ms.push_back(bench::medianMs([&] { field.detect(image, &field_result); }, 9, 2));
    sobel_ms.push_back(result.sobel_ms);
    objects_ms.push_back(result.objects_ms);
    hough_ms.push_back(result.hough_ms);
    horizon_ms.push_back(result.horizon_ms);
    fld_ms.push_back(bench::medianMs([&] {
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      fld->detect(grey, segments);
    }, 9, 2));
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
  const double ours = median(ours_ms), fld_time = median(fld_ms);
  std::printf("\n%s: %zu frames %dx%d, time only (accuracy: make eval)\n", title.c_str(), frames.size(), frames[0].cols,
              frames[0].rows);
  std::printf("  %-46s %8.3f ms   (frames: %.3f to %.3f ms)\n", "ours: Sobel + RLE Hough + horizon", ours,
              *std::min_element(ours_ms.begin(), ours_ms.end()), *std::max_element(ours_ms.begin(), ours_ms.end()));
  std::printf("  %-46s %8.3f / %.3f / %.3f / %.3f ms\n", "  Sobel / edge objects / Hough / horizon", median(sobel_ms),
              median(objects_ms), median(hough_ms), median(horizon_ms));
  std::printf("  %-46s %8d of %zu\n", "  frames whose line budget ran out", budget_cut, frames.size());
  std::printf("  %-46s %8.3f ms\n", "field stage (colour followed, boundary)", median(field_ms));
  printPeer("cvtColor + FastLineDetector", fld_time, ours);
  printPeer("cvtColor + LSD", median(lsd_ms), ours);
  printPeer("cvtColor + Gauss + Canny + HoughLinesP", median(houghp_ms), ours);
  std::printf("  %-46s %8.2f x    (target <= 0.5)\n", "ours / FastLineDetector", ours / fld_time);
  return {{key + "frames", double(frames.size())},
          {key + "frame_ms", ours},
          {key + "sobel_ms", median(sobel_ms)},
          {key + "objects_ms", median(objects_ms)},
          {key + "hough_ms", median(hough_ms)},
          {key + "horizon_ms", median(horizon_ms)},
          {key + "frame_fld_ms", fld_time},
          {key + "frame_lsd_ms", median(lsd_ms)},
          {key + "frame_houghp_ms", median(houghp_ms)},
          {key + "ratio_to_fld", ours / fld_time},
          {key + "frames_budget_cut", double(budget_cut)},
          {key + "field_ms", median(field_ms)}};
}

// Everything measured on the simulator frames: per-frame medians of each method's time, and the
// line scores against the exact edges.
struct SimulatorRun {
  std::vector<double> sobel, opencv_sobel, opencv_derivatives, total, hough, objects, hough_only;
  std::vector<double> votes_only, no_ridge, paper_pairs, houghp, houghs, fld, lsd, horizon_err;
  MatchScore ours, opencv, no_ridge_score, paper_pairs_score, fld_score, lsd_score;
  uint64_t pairs_rle = 0, pairs_global = 0;
};

// What each frame is run through (buffers kept across frames, as a node keeps them).
struct Methods {
  LandmarkOptions options;
  LandmarkDetector detector;
  Sobel5 sobel5;
  LandmarkResult result;
  EdgeObjectFinder finder;
  RleHough rle_hough;
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  cv::Mat grey, edges, cv_edges, gx, gy;
  OpencvSobelBuffers cv_buffers;
};

// The lines each method found on one frame, for scoring.
struct FrameLines {
  std::vector<DetectedLine> no_ridge, paper_pairs;
  std::vector<cv::Vec4i> houghp;
  std::vector<cv::Vec4f> fld, lsd;
};

// Our Sobel against OpenCV's, then our landmark step, whole and in parts.
void timeOurs(const SimFrame& frame, Methods& m, SimulatorRun* run, FrameLines* lines) {
  run->sobel.push_back(bench::medianMs([&] { m.sobel5.edges(frame.image, m.options.edge_gain, &m.edges); }, 30, 3));
  run->opencv_sobel.push_back(bench::medianMs([&] { opencvSobel(frame.image, m.options.edge_gain, &m.cv_buffers, &m.cv_edges); }, 10, 2));
  // cv::Sobel's two derivative passes alone (no magnitude): a lower bound for OpenCV.
  run->opencv_derivatives.push_back(bench::medianMs([&] {
    cv::Sobel(frame.image, m.gx, CV_16S, 1, 0, 5);
    cv::Sobel(frame.image, m.gy, CV_16S, 0, 1, 5);
  }, 10, 2));
  // The whole landmark step, and the Hough + horizon step alone on the same edge image.
  run->total.push_back(bench::medianMs([&] { m.detector.detectInImage(frame.image, m.options, &m.result); }, 15, 2));
  run->hough.push_back(bench::medianMs([&] { m.detector.detectInEdges(m.edges, m.options, &m.result); }, 15, 2));
  // Its two parts: the RLE of the edge image into edge objects, and the Hough on them.
  run->objects.push_back(bench::medianMs([&] { m.finder.find(m.edges, m.options.objects); }, 15, 2));
  std::vector<DetectedLine> hough_lines;
  HoughStats stats;
  const uint8_t ridge = m.options.objects.gray_threshold;
  run->hough_only.push_back(bench::medianMs([&] {
    m.rle_hough.detect(m.finder, m.edges, ridge, m.options.hough, &hough_lines, &stats);
  }, 15, 2));
  // What a 5x speed-up over HoughLinesP has to fit in (docs/performance.md): the first sampling round's
  // votes and seed ordering, no peak refined (no failed peaks allowed ends it there); the
  // Hough refining by least squares on the run pixels instead of the sub-pixel ridge fit; and
  // with the paper's own pair count (eq. 4, margin 1, not 3).
  HoughOptions votes_only = m.options.hough, paper = m.options.hough;
  votes_only.max_failed_peaks = 0;
  paper.sampling_margin = 1;
  run->votes_only.push_back(bench::medianMs([&] {
    m.rle_hough.detect(m.finder, m.edges, ridge, votes_only, &hough_lines, &stats);
  }, 15, 2));
  run->no_ridge.push_back(bench::medianMs([&] {
    m.rle_hough.detectOnRuns(m.finder, m.edges.cols, m.edges.rows, m.options.hough, &lines->no_ridge, &stats);
  }, 15, 2));
  run->paper_pairs.push_back(bench::medianMs([&] {
    m.rle_hough.detect(m.finder, m.edges, ridge, paper, &lines->paper_pairs, &stats);
  }, 15, 2));
  run->pairs_rle += m.result.hough.sample_pairs;
  run->pairs_global += m.result.hough.global_sample_pairs;
}

// OpenCV's Hough on the same edge image (thresholded at our gray threshold), and the line
// detectors from the colour frame, as ours (grey conversion included), defaults.
void timePeers(const SimFrame& frame, Methods& m, SimulatorRun* run, FrameLines* lines) {
  cv::Mat binary = m.edges >= m.options.objects.gray_threshold;
  run->houghp.push_back(bench::medianMs([&] {
    cv::HoughLinesP(binary, lines->houghp, 1, CV_PI / 180, 30, m.options.hough.min_line_length_px, m.options.hough.max_gap_px);
  }, 5, 1));
  std::vector<cv::Vec2f> standard;
  run->houghs.push_back(bench::medianMs([&] { cv::HoughLines(binary, standard, 1, CV_PI / 180, 60); }, 5, 1));
  run->fld.push_back(bench::medianMs([&] {
    cv::cvtColor(frame.image, m.grey, cv::COLOR_BGR2GRAY);
    m.fld->detect(m.grey, lines->fld);
  }, 5, 1));
  run->lsd.push_back(bench::medianMs([&] {
    cv::cvtColor(frame.image, m.grey, cv::COLOR_BGR2GRAY);
    m.lsd->detect(m.grey, lines->lsd);
  }, 3, 1));
}

// Recall over the clear edges (contrast >= 30) of the minimum length; a detection is correct
// along any visible edge (faint ones too, and shorter ones). Within 2 deg and 2 px at the truth
// segment (the segments' own accuracy, without the intercept's extrapolation).
void scoreFrame(const SimFrame& frame, const Methods& m, const FrameLines& lines, SimulatorRun* run) {
  const double min_length = m.options.hough.min_line_length_px;
  std::vector<Segment> truth, any_truth;
  for (const EdgeTruth& e : frame.edges) {
    if (std::hypot(e.x2 - e.x1, e.y2 - e.y1) >= min_length) truth.push_back({e.x1, e.y1, e.x2, e.y2});
  }
  for (const EdgeTruth& e : frame.faint_edges) {
    if (std::hypot(e.x2 - e.x1, e.y2 - e.y1) >= 10) any_truth.push_back({e.x1, e.y1, e.x2, e.y2});
  }
  run->ours += scoreSegments(m.result.lines, truth, any_truth, 2.0, 2.0);
  run->opencv += scoreSegments(toLines(lines.houghp), truth, any_truth, 2.0, 2.0);
  run->fld_score += scoreSegments(toLines(lines.fld, min_length), truth, any_truth, 2.0, 2.0);
  run->lsd_score += scoreSegments(toLines(lines.lsd, min_length), truth, any_truth, 2.0, 2.0);
  run->no_ridge_score += scoreSegments(lines.no_ridge, truth, any_truth, 2.0, 2.0);
  run->paper_pairs_score += scoreSegments(lines.paper_pairs, truth, any_truth, 2.0, 2.0);
  if (m.result.horizon.found && frame.horizon_visible) {
    run->horizon_err.push_back(lineAngleDifference(m.result.horizon.line.theta, frame.horizon.theta) * 180 / M_PI);
  }
}

SimulatorRun runSimulatorFrames(const std::vector<SimFrame>& frames) {
  Methods methods;
  SimulatorRun run;
  for (const SimFrame& frame : frames) {
    FrameLines lines;
    timeOurs(frame, methods, &run, &lines);
    timePeers(frame, methods, &run, &lines);
    scoreFrame(frame, methods, lines, &run);
  }
  return run;
}

// The medians printed and written.
std::vector<std::pair<std::string, double>> summarise(const SimulatorRun& r) {
  const double hough = median(r.hough), houghp = median(r.houghp), hough_only = median(r.hough_only);
  return {{"sobel_ms", median(r.sobel)},
          {"opencv_sobel_ms", median(r.opencv_sobel)},
          {"opencv_sobel_derivatives_only_ms", median(r.opencv_derivatives)},
          {"landmark_total_ms", median(r.total)},
          {"hough_ms", hough},
          {"opencv_houghp_ms", houghp},
          {"opencv_hough_ms", median(r.houghs)},
          {"speedup_vs_houghp", houghp / hough},
          {"edge_objects_ms", median(r.objects)},
          {"hough_only_ms", hough_only},
          {"speedup_vs_houghp_hough_only", houghp / hough_only},
          {"recall", r.ours.recall()},
          {"precision", r.ours.precision()},
          {"opencv_recall", r.opencv.recall()},
          {"opencv_precision", r.opencv.precision()},
          {"fld_ms", median(r.fld)},
          {"fld_recall", r.fld_score.recall()},
          {"fld_precision", r.fld_score.precision()},
          {"lsd_ms", median(r.lsd)},
          {"lsd_recall", r.lsd_score.recall()},
          {"lsd_precision", r.lsd_score.precision()},
          {"sample_pairs_rle", double(r.pairs_rle) / kFrames},
          {"sample_pairs_global", double(r.pairs_global) / kFrames},
          {"hough_votes_only_ms", median(r.votes_only)},
          {"hough_no_ridge_ms", median(r.no_ridge)},
          {"recall_no_ridge", r.no_ridge_score.recall()},
          {"hough_margin1_ms", median(r.paper_pairs)},
          {"recall_margin1", r.paper_pairs_score.recall()},
          {"horizon_err_deg_median", r.horizon_err.empty() ? -1.0 : median(r.horizon_err)}};
}

void printTimes(const std::map<std::string, double>& v) {
  const double sobel = v.at("sobel_ms"), total = v.at("landmark_total_ms"), hough = v.at("hough_ms");
  const double houghp = v.at("opencv_houghp_ms"), hough_only = v.at("hough_only_ms"), objects = v.at("edge_objects_ms");
  std::printf("rle_vision landmark benchmark: %d simulator frames 640x480 (config/scene_default.yaml, walking gait)\n", kFrames);
  std::printf("medians over frames of per-frame medians, one thread pinned to one CPU\n");
  std::printf("  %-46s %8.3f ms\n", "our 5x5 Sobel (3 channels, max magnitude)", sobel);
  std::printf("  %-46s %8.3f ms   (ours %.1fx faster)\n", "OpenCV cv::Sobel ksize 5, same job", v.at("opencv_sobel_ms"),
              v.at("opencv_sobel_ms") / sobel);
  std::printf("  %-46s %8.3f ms   (ours %.1fx faster)\n", "OpenCV cv::Sobel x and y only (no magnitude)",
              v.at("opencv_sobel_derivatives_only_ms"), v.at("opencv_sobel_derivatives_only_ms") / sobel);
  std::printf("  %-46s %8.3f ms   (target <= 3)\n", "landmark total: Sobel + RLE Hough + horizon", total);
  printPeer("cvtColor + FastLineDetector (defaults)", v.at("fld_ms"), total);
  printPeer("cvtColor + LSD (LSD_REFINE_STD)", v.at("lsd_ms"), total);
  std::printf("  %-46s %8.3f ms\n", "RLE Hough + horizon on the edge image", hough);
  std::printf("  %-46s %8.3f ms\n", "  of which: RLE into edge objects", objects);
  std::printf("  %-46s %8.3f ms\n", "  of which: the Hough on the edge objects", hough_only);
  std::printf("  %-46s %8.3f ms   (ours %.1fx faster in all, %.1fx the Hough alone)\n", "cv::HoughLinesP on the same edge image",
              houghp, houghp / hough, houghp / hough_only);
  std::printf("  %-46s %8.3f ms\n", "cv::HoughLines on the same edge image", v.at("opencv_hough_ms"));
}

void printAccuracy(const SimulatorRun& r, const std::map<std::string, double>& v, double min_length) {
  std::printf("  line recall / precision, ours: %.3f / %.3f  (%d truth edges >= 30 px)\n", r.ours.recall(), r.ours.precision(),
              r.ours.truths);
  std::printf("  line recall / precision, HoughLinesP: %.3f / %.3f\n", r.opencv.recall(), r.opencv.precision());
  std::printf("  line recall / precision, FastLineDetector: %.3f / %.3f (its segments >= %.0f px)\n", r.fld_score.recall(),
              r.fld_score.precision(), min_length);
  std::printf("  line recall / precision, LSD: %.3f / %.3f (the same)\n", r.lsd_score.recall(), r.lsd_score.precision());
  std::printf("  5x HoughLinesP means <= %.3f ms for the RLE and the Hough; of it, before any refinement:\n",
              v.at("opencv_houghp_ms") / 5);
  std::printf("  %-46s %8.3f ms\n", "  the RLE into edge objects", v.at("edge_objects_ms"));
  std::printf("  %-46s %8.3f ms\n", "  first sampling round: votes, seeds ordered", v.at("hough_votes_only_ms"));
  std::printf("  %-46s %8.3f ms   (recall / precision %.3f / %.3f)\n", "the Hough without the sub-pixel ridge fit",
              v.at("hough_no_ridge_ms"), r.no_ridge_score.recall(), r.no_ridge_score.precision());
  std::printf("  %-46s %8.3f ms   (recall / precision %.3f / %.3f)\n", "the Hough with eq. 4's pairs at margin 1",
              v.at("hough_margin1_ms"), r.paper_pairs_score.recall(), r.paper_pairs_score.precision());
  std::printf("  sample pairs per frame: RLE per object %.0f, global random Hough (eq. 4) %.0f\n", v.at("sample_pairs_rle"),
              v.at("sample_pairs_global"));
  std::printf("  horizon angle error, median: %.3f deg over %zu frames\n", v.at("horizon_err_deg_median"), r.horizon_err.size());
}

}  // namespace

// rle_vision_bench_landmark [SOURCE_DIR [JSON [UAV_FRAMES_DIR [ROBOT_FRAMES_DIR]]]]
int main(int argc, char** argv) {
  const std::string source_dir = argc > 1 ? argv[1] : RLE_VISION_SOURCE_DIR;
  const std::string json_path = argc > 2 ? argv[2] : source_dir + "/bench/measured/landmark.json";
  bench::pinToOneCpu();
  cv::setNumThreads(1);

  const SceneSimulator simulator(loadSceneConfig(source_dir + "/config/scene_default.yaml"));
  std::vector<SimFrame> frames;
  for (int i = 0; i < kFrames; ++i) frames.push_back(simulator.render(7 * i, 7 * i / 30.0));
  const SimulatorRun run = runSimulatorFrames(frames);
  std::vector<std::pair<std::string, double>> values = summarise(run);
  const std::map<std::string, double> by_key(values.begin(), values.end());
  printTimes(by_key);
  printAccuracy(run, by_key, LandmarkOptions().hough.min_line_length_px);
  if (argc > 3 && argv[3][0] != '\0') {
    const Values real = benchRealFrames(loadLabelledFrames(argv[3]), "real_", std::string("UAV frames of ") + argv[3]);
    values.insert(values.end(), real.begin(), real.end());
  }
  if (argc > 4) {
    const Values msl = benchRealFrames(loadEveryFifteenth(argv[4]), "msl_", std::string("indoor robot frames of ") + argv[4]);
    values.insert(values.end(), msl.begin(), msl.end());
  }
  bench::writeJson(json_path, values);
  std::printf("wrote %s\n", json_path.c_str());
  return 0;
}
