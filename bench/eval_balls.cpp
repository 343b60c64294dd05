// make eval (balls): a colour class calibrated from one labelled folder (rle_vision_calibrate's
// core), then ball recall and blob precision on other folders, ours against OpenCV's
// cvtColor + inRange + connectedComponentsWithStats at the same range, one run, one thread.
//
//   rle_vision_eval_balls --calibrate DIR [--label-class N] [--json OUT] DIR...
//
// Folders hold images with YOLO label files beside them; scoring: ball_scoring.h.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ball_scoring.h"
#include "harness.h"
#include "rle_vision/pipeline/camera_stream.h"
#include "rle_vision/learning/color_calibration.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/io/horizon_model_file.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/io/yolo_labels.h"
#include "rle_vision/field/field_detector.h"

namespace {

using namespace rle_vision;

using bench::BallMethods;
using bench::BallScore;
using Score = BallScore;

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
    const double ms = bench::msSince(start);
    std::vector<cv::Point2d> blobs;
    for (const TrackedBlob& b : frame.blobs) {
      if (b.region.area >= bench::kMinBallBlobArea) blobs.emplace_back(b.region.cx, b.region.cy);
    }
    bench::scoreBlobs(blobs, bench::ballTruth(readYoloBoxes(yoloLabelPath(paths[i]), label_class, bgr.size()), frame.field.boundary), ms, s);
  }
}

FolderScores evaluateFolder(const std::string& folder, int label_class, const ColorClass& ball, BallMethods* methods) {
  FolderScores f;
  f.folder = folder;
  learnedSequence(imagesInFolder(folder), ball, label_class, &f.learned);
  for (const std::string& path : imagesInFolder(folder)) {
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    if (bgr.empty()) throw std::runtime_error(path + ": cannot read the image");
    FieldResult field;
    FieldDetector().detect(bgr, &field);  // the field colour seeded on this frame alone
    const bench::BallTruth truth = bench::ballTruth(readYoloBoxes(yoloLabelPath(path), label_class, bgr.size()), field.boundary);
    methods->ours(bgr, truth, field, &f.ours, &f.on_field);
    methods->opencv(bgr, truth, &f.opencv);
  }
  return f;
}

CalibrationResult calibrate(const std::string& folder, int label_class) {
  std::vector<CalibrationExample> examples;
  for (const std::string& path : imagesInFolder(folder)) examples.push_back(readYoloExample(path, label_class));
  if (examples.empty()) throw std::runtime_error(folder + ": no images to calibrate from");
  return calibrateColorClass(examples, "ball");
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
      json << (m ? ", \"" : "\"") << kMethods[m].first << "\": " << bench::ballScoreJson(f.*kMethods[m].second);
    }
    json << "}";
  }
  json << "\n  },\n  \"methods\": {";
  for (size_t m = 0; m < kMethods.size(); ++m) {
    printRow("all", kMethods[m].first, total.*kMethods[m].second);
    json << (m ? ", \"" : "\"") << kMethods[m].first << "\": " << bench::ballScoreJson(total.*kMethods[m].second);
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
  if (calibrate_dir.empty() || folders.empty() || !bench::isWholeNumber(label_class, 6)) {
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
