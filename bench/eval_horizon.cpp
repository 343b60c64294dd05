// make eval (horizon): our landmark path against line-detector baselines on real labelled
// frames, in one run, one thread pinned to one CPU.
//
//   rle_vision_eval_horizon DIR [--params FILE] [--json OUT]
//
// DIR holds label.csv ("filename,slope,offset" or "filename,has_horizon,slope,offset"; the
// horizon is y = slope x + offset H) and the images (in DIR/images/ or DIR/). Per method: pass
// rate (angle error < 5 deg and Hesse distance error < 5% H; a frame without a horizon passes
// when nothing is reported), found rate, angle and distance errors over the frames where a
// horizon was reported, ms per frame, and for the line detectors the share of frames where a
// segment of 40 px or more lies on the true horizon. The baselines' horizon is their longest
// segment within 45 deg of level (OpenCV FastLineDetector, LSD, and Gauss + Canny + HoughLinesP).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/fast_line_detector.hpp>

#include "harness.h"
#include "eval/horizon_metrics.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/io/landmark_params_file.h"

namespace {

using namespace rle_vision;
using eval::HorizonLabel;

struct Segment4 {
  double x1, y1, x2, y2;
};

// What a method reports for one frame.
struct Detection {
  bool found = false;
  ImageLine horizon;
  double confidence = 1;
  std::vector<Segment4> segments;
};

struct MethodScore {
  std::string name;
  bool line_detector = true;  // reports segments ("on the horizon" rate)
  int frames = 0, passed = 0, found = 0, on_horizon = 0, confident = 0, confident_passed = 0;
  std::vector<double> angle_errors, distance_errors, ms;
  double mean(const std::vector<double>& v) const {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / v.size();
  }
  double median(std::vector<double> v) const {
    if (v.empty()) return 0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  }
};

std::vector<HorizonLabel> readLabels(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the labels");
  std::vector<HorizonLabel> labels;
  std::string line;
  std::getline(in, line);  // header
  const bool with_flag = line.find("has_horizon") != std::string::npos;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string f; std::getline(row, f, ',');) fields.push_back(f);
    HorizonLabel label;
    label.file = fields.at(0);
    size_t k = 1;
    if (with_flag) {
      const std::string flag = fields.at(k++);
      label.has_horizon = flag == "true" || flag == "True" || flag == "1";
    }
    if (label.has_horizon) {
      label.slope = std::stod(fields.at(k));
      label.offset = std::stod(fields.at(k + 1));
    }
    labels.push_back(label);
  }
  return labels;
}

// The longest segment within 45 deg of level, as a horizon.
Detection longestLevelSegment(std::vector<Segment4> segments) {
  Detection d;
  double longest = 0;
  for (const Segment4& s : segments) {
    const double length = std::hypot(s.x2 - s.x1, s.y2 - s.y1);
    if (std::fabs(s.y2 - s.y1) > std::fabs(s.x2 - s.x1) || length <= longest) continue;
    longest = length;
    d.found = true;
    d.horizon = lineThroughPoints(s.x1, s.y1, s.x2, s.y2);
  }
  d.segments = std::move(segments);
  return d;
}

template <typename Vec4>
std::vector<Segment4> toSegments(const std::vector<Vec4>& lines) {
  std::vector<Segment4> out;
  for (const Vec4& l : lines) {
    out.push_back({static_cast<double>(l[0]), static_cast<double>(l[1]), static_cast<double>(l[2]), static_cast<double>(l[3])});
  }
  return out;
}

void score(MethodScore* m, const HorizonLabel& label, const Detection& d, int width, int height, double ms) {
  ++m->frames;
  m->ms.push_back(ms);
  m->found += d.found;
  const bool confident = d.found && d.confidence >= 0.5;
  m->confident += confident;
  if (!label.has_horizon) {
    m->passed += !d.found;
    return;
  }
  const ImageLine truth = label.line(height);
  for (const Segment4& s : d.segments) {
    if (eval::segmentOnHorizon(s.x1, s.y1, s.x2, s.y2, truth, height)) {
      ++m->on_horizon;
      break;
    }
  }
  if (!d.found) return;
  const eval::HorizonError e = eval::horizonError(d.horizon, truth, width, height);
  m->angle_errors.push_back(e.angle_deg);
  m->distance_errors.push_back(e.distance_px);
  const bool pass = eval::passes(e, height);
  m->passed += pass;
  m->confident_passed += confident && pass;
}

void report(const std::vector<MethodScore>& methods, const std::string& dir, const std::string& json_path) {
  std::printf("%-34s %6s %6s %8s %8s %9s %9s %10s %8s\n", "method", "pass", "found", "angle", "angle", "distance",
              "on hor.", "conf>=0.5", "ms/frame");
  std::printf("%-34s %6s %6s %8s %8s %9s %9s %10s %8s\n", "", "%", "%", "mean deg", "med deg", "mean px", "%",
              "pass %", "mean");
  std::ostringstream json;
  json << "{\n  \"data\": \"" << dir << "\",\n  \"machine\": \"" << bench::machineName() << "\",\n  \"date\": \""
       << bench::todayUtc()
       << "\",\n  \"frames\": " << (methods.empty() ? 0 : methods[0].frames) << ",\n  \"methods\": {";
  for (size_t i = 0; i < methods.size(); ++i) {
    const MethodScore& m = methods[i];
    const double n = std::max(1, m.frames);
    const double pass = 100.0 * m.passed / n, found = 100.0 * m.found / n, on = 100.0 * m.on_horizon / n;
    const double confident_pass = m.confident ? 100.0 * m.confident_passed / m.confident : 100.0;
    std::printf("%-34s %6.1f %6.1f %8.2f %8.2f %9.1f %9s %10.1f %8.2f\n", m.name.c_str(), pass, found,
                m.mean(m.angle_errors), m.median(m.angle_errors), m.mean(m.distance_errors),
                m.line_detector ? cv::format("%.1f", on).c_str() : "-", confident_pass, m.mean(m.ms));
    json << (i ? "," : "") << "\n    \"" << m.name << "\": {\"pass_pct\": " << pass << ", \"found_pct\": " << found
         << ", \"angle_error_mean_deg\": " << m.mean(m.angle_errors)
         << ", \"angle_error_median_deg\": " << m.median(m.angle_errors)
         << ", \"distance_error_mean_px\": " << m.mean(m.distance_errors)
         << ", \"distance_error_median_px\": " << m.median(m.distance_errors)
         << ", \"on_horizon_pct\": " << (m.line_detector ? on : -1) << ", \"confident_frames\": " << m.confident
         << ", \"confident_pass_pct\": " << confident_pass << ", \"ms_per_frame\": " << m.mean(m.ms)
         << ", \"ms_per_frame_median\": " << m.median(m.ms) << "}";
  }
  json << "\n  }\n}\n";
  if (!json_path.empty()) {
    std::ofstream(json_path) << json.str();
    std::printf("wrote %s\n", json_path.c_str());
  }
}

template <typename Body>
double timeMs(Body body) {
  const auto start = std::chrono::steady_clock::now();
  body();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: rle_vision_eval_horizon DIR [--params FILE] [--json OUT]\n";
    return 2;
  }
  const std::string dir = argv[1];
  std::string params_file, json_path;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string arg = argv[i];
    (arg == "--params" ? params_file : json_path) = argv[i + 1];
  }
  bench::pinToOneCpu();
  cv::setNumThreads(1);
  std::vector<HorizonLabel> labels;
  LandmarkOptions options;
  try {
    labels = readLabels(dir + "/label.csv");
    if (!params_file.empty()) options = loadLandmarkParams(params_file);
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_eval_horizon: " << e.what() << "\n";
    return 2;
  }
  LandmarkDetector detector;
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  std::vector<MethodScore> methods(4);
  methods[0].name = "ours (rle_vision, defaults)";
  methods[1].name = "FastLineDetector (longest level)";
  methods[2].name = "LSD (longest level)";
  methods[3].name = "HoughLinesP (longest level)";
  int missing = 0;
  for (const HorizonLabel& label : labels) {
    cv::Mat image = cv::imread(dir + "/images/" + label.file, cv::IMREAD_COLOR);
    if (image.empty()) image = cv::imread(dir + "/" + label.file, cv::IMREAD_COLOR);
    if (image.empty()) {
      ++missing;
      continue;
    }
    LandmarkResult result;
    double ms = timeMs([&] { detector.detectInImage(image, options, &result); });
    Detection ours;
    ours.found = result.horizon.found;
    ours.horizon = result.horizon.line;
    ours.confidence = result.horizon.confidence;
    for (const DetectedLine& l : result.lines) ours.segments.push_back({l.x1, l.y1, l.x2, l.y2});
    score(&methods[0], label, ours, image.cols, image.rows, ms);

    cv::Mat gray;
    std::vector<cv::Vec4f> fld_lines, lsd_lines;
    ms = timeMs([&] {
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
      fld->detect(gray, fld_lines);
    });
    score(&methods[1], label, longestLevelSegment(toSegments(fld_lines)), image.cols, image.rows, ms);
    ms = timeMs([&] {
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
      lsd->detect(gray, lsd_lines);
    });
    score(&methods[2], label, longestLevelSegment(toSegments(lsd_lines)), image.cols, image.rows, ms);
    std::vector<cv::Vec4i> hough_lines;
    ms = timeMs([&] {
      cv::Mat blurred, edges;
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
      cv::GaussianBlur(gray, blurred, cv::Size(5, 5), 1.5);
      cv::Canny(blurred, edges, 30, 90);
      cv::HoughLinesP(edges, hough_lines, 1, CV_PI / 180, 40, 40, 5);
    });
    score(&methods[3], label, longestLevelSegment(toSegments(hough_lines)), image.cols, image.rows, ms);
  }
  std::printf("rle_vision eval (horizon): %zu labelled frames in %s%s; one thread pinned to one CPU\n", labels.size(),
              dir.c_str(), missing ? cv::format(" (%d images missing)", missing).c_str() : "");
  std::printf("pass: angle error < %.0f deg and Hesse distance (from the image centre) error < %.0f%% of H; "
              "errors over the frames with a horizon reported; on hor.: a segment >= %.0f px within %.0f deg and "
              "%.0f%% H of the true horizon\n",
              eval::kPassAngleDeg, 100 * eval::kPassDistanceShareOfHeight, eval::kOnHorizonMinLengthPx,
              eval::kOnHorizonAngleDeg, 100 * eval::kOnHorizonDistanceShareOfHeight);
  report(methods, dir, json_path);
  return missing == static_cast<int>(labels.size()) ? 2 : 0;
}
