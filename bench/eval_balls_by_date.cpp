// make eval (balls, grouped by date): the ball class calibrated on one date (one hall and its
// light: rle_vision_calibrate's core on every labelled frame of that date) and scored on each
// other date, every date calibrating in turn (DESIGN §5a: grouped cross-validation; the worst
// pair is the result). A team calibrates in its own hall and plays in another; this is that.
// Per pair: ours with the fixed range, ours keeping only blobs on the field side (the tracker's
// on_field_classes, margin 10 px, the field colour seeded on each frame alone), and OpenCV's
// cvtColor + inRange + connectedComponentsWithStats at the same range. Recall is counted over
// every labelled ball and over the balls on the field side (ball_scoring.h).
//
//   rle_vision_eval_balls_by_date [--label-class N] [--non-field-penalty P] [--json OUT] DIR
//
// --non-field-penalty sets the field stage's field_non_field_penalty (default 1.0).
//
// DIR's folders are the dates; each holds images (or folders of them) with YOLO labels beside.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "ball_scoring.h"
#include "field_options_arg.h"
#include "harness.h"
#include "rle_vision/io/yolo_labels.h"
#include "rle_vision/learning/color_calibration.h"

namespace {

using namespace rle_vision;
using bench::BallScore;

using Date = bench::LabelledDate;

// The methods' scores on one scored date (or a sum of them).
struct PairScore {
  BallScore ours, on_field, opencv;
  void add(const PairScore& o) { ours.add(o.ours), on_field.add(o.on_field), opencv.add(o.opencv); }
};

const std::vector<std::pair<const char*, BallScore PairScore::*>> kMethods = {
    {"ours", &PairScore::ours}, {"ours_on_field", &PairScore::on_field}, {"opencv", &PairScore::opencv}};
const char* const kMethodNames[] = {"ours, calibrated range (fixed)", "ours, on the field side only",
                                    "OpenCV cvtColor+inRange+connectedComponents"};

// The frames' field boundaries, each found once (each frame alone) and kept for every pair.
struct FieldCache {
  FieldOptions options;
  std::map<std::string, FieldResult> results;
};

const FieldResult& fieldOf(const std::string& path, const cv::Mat& bgr, FieldCache* cache) {
  auto found = cache->results.find(path);
  if (found != cache->results.end()) return found->second;
  FieldResult& field = cache->results[path];
  FieldDetector(cache->options).detect(bgr, &field);
  return field;
}

PairScore scoreDate(const Date& date, const ColorClass& ball, int label_class, FieldCache* fields) {
  PairScore s;
  bench::BallMethods methods(ball);
  for (const std::string& path : date.images) {
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    if (bgr.empty()) throw std::runtime_error(path + ": cannot read the image");
    const FieldResult& field = fieldOf(path, bgr, fields);
    const bench::BallTruth truth =
        bench::ballTruth(readYoloBoxes(yoloLabelPath(path), label_class, bgr.size()), field.boundary);
    methods.ours(bgr, truth, field, &s.ours, &s.on_field);
    methods.opencv(bgr, truth, &s.opencv);
  }
  return s;
}

void printRow(const std::string& pair, const char* method, const BallScore& s) {
  std::printf("%-20s %-44s %6d %7.1f %7.1f %6d %9.1f %8.3f\n", pair.c_str(), method, s.balls, s.recall(),
              s.fieldRecall(), s.blobs, s.precision(), s.msPerFrame());
}

void addValues(const std::string& prefix, const PairScore& s, std::vector<std::pair<std::string, double>>* values) {
  for (const auto& m : kMethods) {
    bench::addBallScoreValues(prefix + "." + m.first, s.*m.second, values);
  }
}

// Every date calibrates; every other date is scored; the worst pair per method and figure.
void run(const std::vector<Date>& dates, int label_class, const FieldOptions& field_options, const std::string& json) {
  std::printf("%-20s %-44s %6s %7s %7s %6s %9s %8s\n", "calibrated->scored", "method", "balls", "recall",
              "field-r", "blobs", "precision", "ms/frame");
  FieldCache fields{field_options, {}};
  std::vector<std::pair<std::string, double>> values;
  PairScore all;
  std::map<std::string, double> worst;
  for (const Date& calibration : dates) {
    const ColorClass ball = bench::calibrateBall({&calibration}, label_class);
    for (const Date& scored : dates) {
      if (&scored == &calibration) continue;
      const PairScore s = scoreDate(scored, ball, label_class, &fields);
      const std::string pair = calibration.name + "->" + scored.name;
      for (size_t m = 0; m < kMethods.size(); ++m) printRow(pair, kMethodNames[m], s.*kMethods[m].second);
      addValues("pairs." + calibration.name + "_to_" + scored.name, s, &values);
      all.add(s);
      for (const auto& m : kMethods) {
        const BallScore& b = s.*m.second;
        if (b.balls == 0) continue;
        for (const auto& figure : {std::make_pair("precision_pct", b.precision()), std::make_pair("recall_pct", b.recall()),
                                   std::make_pair("recall_on_field_pct", b.fieldRecall())}) {
          const std::string key = std::string("worst.") + m.first + "." + figure.first;
          worst[key] = worst.count(key) ? std::min(worst[key], figure.second) : figure.second;
        }
      }
    }
  }
  for (size_t m = 0; m < kMethods.size(); ++m) printRow("all pairs", kMethodNames[m], all.*kMethods[m].second);
  for (const auto& w : worst) std::printf("%-44s %6.1f\n", w.first.c_str(), w.second);
  addValues("all", all, &values);
  for (const auto& w : worst) values.emplace_back(w.first, w.second);
  if (!json.empty()) bench::writeJson(json, values);
}

}  // namespace

int main(int argc, char** argv) {
  std::string root, json, label_class = "0", problem;
  FieldOptions field_options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--json" || arg == "--label-class") && i + 1 < argc) {
      (arg == "--json" ? json : label_class) = argv[++i];
    } else if (arg == "--non-field-penalty" && i + 1 < argc) {
      if (!bench::parseNonFieldPenalty(argv[++i], &field_options, &problem)) {
        std::cerr << "rle_vision_eval_balls_by_date: " << problem << "\n";
        return 2;
      }
    } else {
      root = arg;
    }
  }
  const std::vector<Date> dates = bench::labelledDates(root);
  if (dates.size() < 2 || !bench::isWholeNumber(label_class, 6)) {
    std::cerr << "usage: rle_vision_eval_balls_by_date [--label-class N] [--non-field-penalty P] [--json OUT] DIR (its "
                 "folders: two or more dates)\n";
    return 2;
  }
  bench::pinToOneCpu();
  try {
    run(dates, std::stoi(label_class), field_options, json);
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_eval_balls_by_date: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
