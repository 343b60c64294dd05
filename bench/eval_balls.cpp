// make eval (balls): a colour class calibrated from one labelled folder (rle_vision_calibrate's
// core), then ball recall and blob precision on other folders, ours against OpenCV's
// cvtColor + inRange + connectedComponentsWithStats at the same range, one run, one thread.
//
//   rle_vision_eval_balls --calibrate DIR [--label-class N] [--json OUT] DIR...
//
// Folders hold images with YOLO label files beside them. A ball counts as found when a blob of
// the class (area >= 20 px) has its centroid inside the ball's labelled box; blob precision is
// the share of such blobs whose centroid lies inside some ball box.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "harness.h"
#include "eval/opencv_pipeline.h"
#include "rle_vision/pipeline/camera_stream.h"
#include "rle_vision/learning/color_calibration.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/io/horizon_model_file.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/io/yolo_labels.h"
#include "rle_vision/field/field_detector.h"

namespace {

using namespace rle_vision;

constexpr uint32_t kMinBlobArea = 20;
constexpr double kOnFieldMarginPx = 10;  // the tracker's on_field_margin_px default

struct Score {
  int frames = 0, balls = 0, found = 0, blobs = 0, on_ball = 0;
  double ms = 0;
  void add(const Score& o) {
    frames += o.frames, balls += o.balls, found += o.found, blobs += o.blobs, on_ball += o.on_ball, ms += o.ms;
  }
  double recall() const { return balls ? 100.0 * found / balls : 0; }
  double precision() const { return blobs ? 100.0 * on_ball / blobs : 100; }
  double msPerFrame() const { return frames ? ms / frames : 0; }
};

bool inside(const cv::Point2d& p, const cv::Rect& box) {
  return p.x >= box.x && p.x <= box.br().x - 1 && p.y >= box.y && p.y <= box.br().y - 1;
}

void score(const std::vector<cv::Point2d>& blobs, const std::vector<cv::Rect>& balls, double ms, Score* s) {
  ++s->frames;
  s->ms += ms;
  s->balls += static_cast<int>(balls.size());
  s->blobs += static_cast<int>(blobs.size());
  for (const cv::Rect& ball : balls) {
    bool found = false;
    for (const cv::Point2d& b : blobs) found = found || inside(b, ball);
    s->found += found;
  }
  for (const cv::Point2d& b : blobs) {
    bool on_ball = false;
    for (const cv::Rect& ball : balls) on_ball = on_ball || inside(b, ball);
    s->on_ball += on_ball;
  }
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The methods on one frame.
class BallMethods {
 public:
  explicit BallMethods(const ColorClass& ball) : table_({ball}), opencv_({ball}) {}

  // `on_field`: the same blobs less those whose lowest point (below the centroid) lies more than
  // the tracker's default margin above the field boundary (the field colour seeded on the frame).
  void ours(const cv::Mat& bgr, const std::vector<cv::Rect>& balls, Score* s, Score* on_field) {
    const auto start = std::chrono::steady_clock::now();
    segmenter_.segment(bgr, PixelFormat::BGR8, table_, &regions_);
    const double ms = msSince(start);
    std::vector<cv::Point2d> blobs, kept;
    FieldResult field;
    FieldDetector().detect(bgr, &field);
    for (const Region& r : regions_) {
      if (r.area < kMinBlobArea) continue;
      blobs.emplace_back(r.cx, r.cy);
      if (!field.boundary.found || field.boundary.heightAbove(r.cx, r.bottom_at_cx) <= kOnFieldMarginPx) {
        kept.emplace_back(r.cx, r.cy);
      }
    }
    score(blobs, balls, ms, s);
    score(kept, balls, ms + field.ms, on_field);
  }

  void opencv(const cv::Mat& bgr, const std::vector<cv::Rect>& balls, Score* s) {
    const auto start = std::chrono::steady_clock::now();
    opencv_.run(bgr, &opencv_blobs_);
    const double ms = msSince(start);
    std::vector<cv::Point2d> blobs;
    for (const OpenCvBlob& b : opencv_blobs_) {
      if (b.area >= static_cast<int>(kMinBlobArea)) blobs.emplace_back(b.cx, b.cy);
    }
    score(blobs, balls, ms, s);
  }

 private:
  ColorTable table_;
  Segmenter segmenter_;
  std::vector<Region> regions_;
  OpenCvPipeline opencv_;  // cvtColor + inRange + connectedComponentsWithStats, 8-connected
  std::vector<OpenCvBlob> opencv_blobs_;
};

struct FolderScores {
  std::string folder;
  Score ours, opencv, learned, on_field;
};

// The folder's images, in name order, as one camera stream at 30 Hz with colour learning
// from blobs (rle_vision_detect --sequence with learning_from_blobs: true).
void learnedSequence(const std::vector<std::string>& paths, const ColorClass& ball, int label_class, Score* s) {
  CameraStreamOptions options;
  options.learning.from_blobs = true;
  options.landmark.horizon.model = horizonModelFromSetting("");  // as the nodes and the CLI weigh horizons
  CameraStream stream({ball}, options);
  CameraStream::Frame frame;
  for (size_t i = 0; i < paths.size(); ++i) {
    const cv::Mat bgr = cv::imread(paths[i], cv::IMREAD_COLOR);
    if (bgr.empty()) throw std::runtime_error(paths[i] + ": cannot read the image");
    const auto start = std::chrono::steady_clock::now();
    stream.process(bgr, static_cast<double>(i) / 30.0, &frame);
    const double ms = msSince(start);
    std::vector<cv::Point2d> blobs;
    for (const TrackedBlob& b : frame.blobs) {
      if (b.region.area >= kMinBlobArea) blobs.emplace_back(b.region.cx, b.region.cy);
    }
    score(blobs, readYoloBoxes(yoloLabelPath(paths[i]), label_class, bgr.size()), ms, s);
  }
}

FolderScores evaluateFolder(const std::string& folder, int label_class, const ColorClass& ball, BallMethods* methods) {
  FolderScores f;
  f.folder = folder;
  learnedSequence(imagesInFolder(folder), ball, label_class, &f.learned);
  for (const std::string& path : imagesInFolder(folder)) {
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    if (bgr.empty()) throw std::runtime_error(path + ": cannot read the image");
    const std::vector<cv::Rect> balls = readYoloBoxes(yoloLabelPath(path), label_class, bgr.size());
    methods->ours(bgr, balls, &f.ours, &f.on_field);
    methods->opencv(bgr, balls, &f.opencv);
  }
  return f;
}

CalibrationResult calibrate(const std::string& folder, int label_class) {
  std::vector<CalibrationExample> examples;
  for (const std::string& path : imagesInFolder(folder)) examples.push_back(readYoloExample(path, label_class));
  if (examples.empty()) throw std::runtime_error(folder + ": no images to calibrate from");
  return calibrateColorClass(examples, "ball");
}

std::string scoreJson(const Score& s) {
  std::ostringstream out;
  out << "{\"frames\": " << s.frames << ", \"balls\": " << s.balls << ", \"found\": " << s.found
      << ", \"recall_pct\": " << s.recall() << ", \"blobs\": " << s.blobs << ", \"blobs_on_ball\": " << s.on_ball
      << ", \"precision_pct\": " << s.precision() << ", \"ms_per_frame\": " << s.msPerFrame() << "}";
  return out.str();
}

void printRow(const std::string& folder, const std::string& method, const Score& s) {
  std::printf("%-12s %-48s %6d %7.1f %6d %9.1f %8.3f\n", folder.c_str(), method.c_str(), s.balls, s.recall(), s.blobs,
              s.precision(), s.msPerFrame());
}

const char* kOurs = "ours, calibrated range (fixed)";
const char* kOpenCv = "OpenCV cvtColor+inRange+connectedComponents";
const char* kLearned = "ours, --sequence, learning from blobs";
const char* kOnField = "ours, calibrated range, on the field side only";

// The methods in the order reported, and where each folder keeps its score.
const std::vector<std::pair<const char*, Score FolderScores::*>> kMethods = {
    {kOurs, &FolderScores::ours}, {kOpenCv, &FolderScores::opencv}, {kLearned, &FolderScores::learned},
    {kOnField, &FolderScores::on_field}};

void report(const std::string& calibrate_dir, const CalibrationResult& calibration,
            const std::vector<FolderScores>& folders, const std::string& json_path) {
  const ColorClass& c = calibration.color_class;
  std::printf("class 'ball' calibrated on %s (%d boxes used, %d dropped): YUV [%d %d %d]..[%d %d %d]\n",
              calibrate_dir.c_str(), calibration.boxes_used, calibration.boxes_dropped, c.min[0], c.min[1], c.min[2],
              c.max[0], c.max[1], c.max[2]);
  std::printf("%-12s %-48s %6s %7s %6s %9s %8s\n", "folder", "method", "balls", "recall", "blobs", "precision",
              "ms/frame");
  FolderScores total;
  std::ostringstream json;
  json << "{\n  \"calibrated_on\": \"" << calibrate_dir << "\",\n  \"machine\": \"" << bench::machineName()
       << "\",\n  \"date\": \"" << bench::todayUtc() << "\",\n  \"range\": {\"min\": [" << int(c.min[0]) << ", "
       << int(c.min[1]) << ", " << int(c.min[2]) << "], \"max\": [" << int(c.max[0]) << ", " << int(c.max[1]) << ", "
       << int(c.max[2]) << "]},\n  \"folders\": {";
  for (size_t i = 0; i < folders.size(); ++i) {
    const FolderScores& f = folders[i];
    const std::string name = f.folder.substr(f.folder.find_last_of('/') + 1);
    json << (i ? "," : "") << "\n    \"" << name << "\": {";
    for (size_t m = 0; m < kMethods.size(); ++m) {
      printRow(name, kMethods[m].first, f.*kMethods[m].second);
      (total.*kMethods[m].second).add(f.*kMethods[m].second);
      json << (m ? ", \"" : "\"") << kMethods[m].first << "\": " << scoreJson(f.*kMethods[m].second);
    }
    json << "}";
  }
  json << "\n  },\n  \"methods\": {";
  for (size_t m = 0; m < kMethods.size(); ++m) {
    printRow("all", kMethods[m].first, total.*kMethods[m].second);
    json << (m ? ", \"" : "\"") << kMethods[m].first << "\": " << scoreJson(total.*kMethods[m].second);
  }
  json << "}\n}\n";
  if (!json_path.empty()) {
    std::ofstream(json_path) << json.str();
    std::printf("wrote %s\n", json_path.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string calibrate_dir, json_path, label_class = "0";
  std::vector<std::string> folders;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--calibrate" || arg == "--json" || arg == "--label-class") && i + 1 < argc) {
      (arg == "--label-class" ? label_class : arg == "--calibrate" ? calibrate_dir : json_path) = argv[++i];
    } else {
      folders.push_back(arg);
    }
  }
  if (calibrate_dir.empty() || folders.empty() || label_class.find_first_not_of("0123456789") != std::string::npos ||
      label_class.empty() || label_class.size() > 6) {
    std::cerr << "usage: rle_vision_eval_balls --calibrate DIR [--label-class N] [--json OUT] DIR...\n";
    return 2;
  }
  bench::pinToOneCpu();
  try {
    const CalibrationResult calibration = calibrate(calibrate_dir, std::stoi(label_class));
    BallMethods methods(calibration.color_class);
    std::vector<FolderScores> scores;
    for (const std::string& folder : folders) {
      scores.push_back(evaluateFolder(folder, std::stoi(label_class), calibration.color_class, &methods));
    }
    report(calibrate_dir, calibration, scores, json_path);
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_eval_balls: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
