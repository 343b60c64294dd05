// make eval (ball verifier, issue 30): grouped cross-validation by date. For each date of DIR in
// turn: the ball class calibrated on each other date (rle_vision_calibrate's core), the smallest
// range holding them all (widened by --widen levels on every channel, 0 by default); its blobs
// on the other dates' frames, the floor's colour (grown by the floor guard's scale, chosen by
// the training dates each held out in turn) taking the floor first, are the candidates a
// verifier (verify/blob_verifier.h: one model per training date, trained without it) is trained
// on (on a labelled ball: positive), as rle_vision_train does; then the held-out date's
// candidates, made the same way, are scored and those at 0.5 or more kept. Beside it, on
// the same frames: the calibrated range alone (what the tracker does without a verifier, and
// what OpenCV's inRange pipeline finds at the same range), and the verifier with the field side
// filter. Recall is over every labelled ball and over the balls on the field side.
//
// --compare-models also trains OpenCV ml's SVM and MLP on the same candidates (not in make eval:
// minutes more) and prints their held-out recall and precision beside the boosted trees'.
// --jobs N: N held-out dates at a time, each thread on its own CPU (make eval: JOBS, 2); the
// figures are the same (the dates share only the loaded frames, read-only, and the training
// draws nothing at random), the time per frame each thread's own.
//
//   rle_vision_eval_verifier [--label-class N] [--widen LEVELS] [--compare-models] [--jobs N] [--json OUT] DIR
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "ball_scoring.h"
#include "harness.h"
#include "verifier_alternatives.h"
#include "rle_vision/io/yolo_labels.h"
#include "rle_vision/learning/color_calibration.h"
#include "rle_vision/verify/blob_verifier.h"
#include "rle_vision/verify/verifier_training.h"

namespace {

using namespace rle_vision;
using bench::BallScore;

using Date = bench::LabelledDate;

struct HeldOutScore {
  BallScore range, loose, verified, verified_on_field;
  BallScore svm, mlp, boost_with_field;  // --compare-models
  int train_candidates = 0, train_positives = 0;
  double verify_ms = 0;  // features and scores, all frames
  int candidates = 0;
  double floor_guard_scale = 1.0;  // chosen on the training dates
  std::string log;                 // how it was chosen, printed in the dates' order
  void add(const HeldOutScore& o) {
    range.add(o.range), loose.add(o.loose), verified.add(o.verified), verified_on_field.add(o.verified_on_field);
    svm.add(o.svm), mlp.add(o.mlp), boost_with_field.add(o.boost_with_field);
    train_candidates += o.train_candidates, train_positives += o.train_positives;
    verify_ms += o.verify_ms, candidates += o.candidates;
  }
};

const std::vector<std::pair<const char*, BallScore HeldOutScore::*>> kMethods = {
    {"range", &HeldOutScore::range}, {"candidates", &HeldOutScore::loose}, {"verified", &HeldOutScore::verified},
    {"verified_on_field", &HeldOutScore::verified_on_field}};
const char* const kMethodNames[] = {"calibrated range alone (= OpenCV inRange)", "candidates (covering range)",
                                    "candidates + verifier", "candidates + verifier, field side only"};

// How far a candidate lies above the frame's field boundary, in image heights (0 without one):
// the feature --compare-models adds. Its centroid, as the features keep it.
float heightAboveField(const FieldResult& field, double cx, double cy, int rows) {
  return field.boundary.found ? static_cast<float>(field.boundary.heightAbove(cx, cy) / rows) : 0.0f;
}

// A labelled frame, read and its field found once: the nested cross-validation reads each
// training frame once per floor guard scale it tries.
struct LoadedFrame {
  cv::Mat bgr;
  std::vector<cv::Rect> balls;
  FieldResult field;
};
using LoadedDates = std::map<const Date*, std::vector<LoadedFrame>>;

LoadedDates loadDates(const std::vector<Date>& dates, int label_class) {
  LoadedDates loaded;
  for (const Date& d : dates) {
    for (const std::string& path : d.images) {
      LoadedFrame f;
      f.bgr = cv::imread(path, cv::IMREAD_COLOR);
      if (f.bgr.empty()) throw std::runtime_error(path + ": cannot read the image");
      f.balls = readYoloBoxes(yoloLabelPath(path), label_class, f.bgr.size());
      FieldDetector().detect(f.bgr, &f.field);
      loaded[&d].push_back(std::move(f));
    }
  }
  return loaded;
}

// The floor's colour as the candidates see it: the frame's field range grown by the floor
// guard's scale (scaledRange), so the floor's outer pixels are the floor's and not the start of
// a candidate.
std::optional<ColorClass> candidatesFloor(const FieldResult& field, double floor_guard_scale) {
  if (!field.colour.found) return std::nullopt;
  return scaledRange(field.colour.range, floor_guard_scale);
}

// The candidates' range: the smallest holding the ball as calibrated on each date, widened.
ColorClass candidateRange(const std::vector<const Date*>& dates, int label_class, int widen) {
  std::vector<ColorClass> calibrated;
  for (const Date* d : dates) calibrated.push_back(bench::calibrateBall({d}, label_class));
  return widenedRange(rangeCovering(calibrated), widen);
}

// The candidates of `dates`' frames (blobs of `range`) and their labels, each date its group;
// the floor's range grown by `floor_guard_scale` first; with `above_field`, also each candidate's
// height above the field boundary.
VerifierTrainingSet collect(const LoadedDates& loaded, const std::vector<const Date*>& dates, const ColorClass& range,
                            double floor_guard_scale, cv::Mat* above_field = nullptr) {
  VerifierTrainingSet set(range, bench::kMinBallBlobArea, floor_guard_scale);
  for (size_t g = 0; g < dates.size(); ++g) {
    set.setGroup(static_cast<int>(g));
    for (const LoadedFrame& f : loaded.at(dates[g])) {
      const int before = set.features().rows;
      set.addFrame(f.bgr, f.balls, f.field.colour.found ? &f.field.colour.range : nullptr);
      for (int i = before; above_field && i < set.features().rows; ++i) {  // features 4 and 5: the centroid's row and column
        const float* x = set.features().ptr<float>(i);
        above_field->push_back(heightAboveField(f.field, x[5] * f.bgr.cols, x[4] * f.bgr.rows, f.bgr.rows));
      }
    }
  }
  return set;
}

// The floor guard's scale chosen on the training dates alone, as rle_vision_train chooses the
// shipped one (chooseFloorGuardScale: grouped cross-validation, each training date held out).
double floorGuardScaleOnTraining(const LoadedDates& loaded, const std::vector<const Date*>& training,
                                 const ColorClass& range, std::string* log) {
  std::vector<VerifierTrainingSet> sets;
  for (double scale : floorGuardScalesTried()) sets.push_back(collect(loaded, training, range, scale));
  std::vector<double> f1;
  const double chosen = chooseFloorGuardScale(sets, &f1);
  for (size_t k = 0; k < sets.size(); ++k) {
    char line[96];
    std::snprintf(line, sizeof(line), "  floor guard scale %.1f: training dates' held-out mean F1 %.3f\n",
                  sets[k].floorGuardScale(), f1[k]);
    *log += line;
  }
  return chosen;
}

using bench::AlternativeModel;

// --compare-models: the candidate kept by each alternative model (the last one also sees the
// candidate's height above the field).
void keepByAlternatives(const std::vector<AlternativeModel>& models, const CandidateFeatures& x, float above_field,
                        const Region& r, std::vector<cv::Point2d> kept_by[3]) {
  cv::Mat row(1, kCandidateFeatureCount + 1, CV_32F);
  std::copy(x.begin(), x.end(), row.ptr<float>());
  row.at<float>(0, kCandidateFeatureCount) = above_field;
  for (size_t k = 0; k < models.size(); ++k) {
    const cv::Mat features = k + 1 < models.size() ? row.colRange(0, kCandidateFeatureCount) : row;
    if (models[k].keep(features)) kept_by[k].emplace_back(r.cx, r.cy);
  }
}

HeldOutScore evaluate(const LoadedDates& loaded, const Date& held_out, const std::vector<const Date*>& training,
                      int label_class, int widen, bool compare_models) {
  HeldOutScore s;
  const ColorClass calibrated = bench::calibrateBall(training, label_class);
  const ColorClass candidates_range = candidateRange(training, label_class, widen);
  s.floor_guard_scale = floorGuardScaleOnTraining(loaded, training, candidates_range, &s.log);
  cv::Mat above_field;
  const VerifierTrainingSet set =
      collect(loaded, training, candidates_range, s.floor_guard_scale, compare_models ? &above_field : nullptr);
  s.train_candidates = static_cast<int>(set.labels().size());
  s.train_positives = set.positives();
  const BlobVerifier verifier = BlobVerifier::trainAcrossGroups(set.features(), set.labels(), set.groups());
  std::vector<AlternativeModel> alternatives;
  if (compare_models) {
    alternatives.emplace_back(AlternativeModel::Kind::kSvm, set.features(), set.labels());
    alternatives.emplace_back(AlternativeModel::Kind::kMlp, set.features(), set.labels());
    cv::Mat with_field;
    cv::hconcat(set.features(), above_field, with_field);
    alternatives.emplace_back(AlternativeModel::Kind::kBoostWithField, with_field, set.labels());
  }
  bench::BallMethods range_alone(calibrated);
  Segmenter segmenter;
  std::vector<Region> regions;
  CandidateFeatures x;
  for (const LoadedFrame& f : loaded.at(&held_out)) {
    const cv::Mat& bgr = f.bgr;
    const FieldResult& field = f.field;
    const bench::BallTruth truth = bench::ballTruth(f.balls, field.boundary);
    BallScore unused;
    range_alone.ours(bgr, truth, field, &s.range, &unused);
    const auto start = std::chrono::steady_clock::now();
    const std::optional<ColorClass> floor = candidatesFloor(field, s.floor_guard_scale);
    candidateRegions(&segmenter, bgr, candidates_range, floor ? &*floor : nullptr, bench::kMinBallBlobArea, &regions);
    std::vector<cv::Point2d> kept, kept_on_field, all, kept_by[3];
    const FrameChroma frame = regions.empty() ? FrameChroma() : frameChroma(bgr);
    for (const Region& r : regions) {
      ++s.candidates;
      all.emplace_back(r.cx, r.cy);
      candidateFeatures(bgr, frame, r, &x);
      if (compare_models) keepByAlternatives(alternatives, x, heightAboveField(field, r.cx, r.cy, bgr.rows), r, kept_by);
      if (verifier.score(x) < 0.5f) continue;
      kept.emplace_back(r.cx, r.cy);
      if (!field.boundary.found || field.boundary.heightAbove(r.cx, r.bottom_at_cx) <= bench::kOnFieldMarginPx) {
        kept_on_field.emplace_back(r.cx, r.cy);
      }
    }
    const double ms = bench::msSince(start);
    s.verify_ms += ms;
    bench::scoreBlobs(all, truth, 0, &s.loose);
    bench::scoreBlobs(kept, truth, ms, &s.verified);
    bench::scoreBlobs(kept_on_field, truth, ms + field.ms, &s.verified_on_field);
    if (compare_models) {
      bench::scoreBlobs(kept_by[0], truth, 0, &s.svm);
      bench::scoreBlobs(kept_by[1], truth, 0, &s.mlp);
      bench::scoreBlobs(kept_by[2], truth, 0, &s.boost_with_field);
    }
  }
  return s;
}

void printRow(const std::string& date, const char* method, const BallScore& b) {
  std::printf("%-10s %-46s %6d %7.1f %7.1f %6d %9.1f %8.3f\n", date.c_str(), method, b.balls, b.recall(),
              b.fieldRecall(), b.blobs, b.precision(), b.msPerFrame());
}

void addValues(const std::string& prefix, const HeldOutScore& s, std::vector<std::pair<std::string, double>>* values) {
  for (const auto& m : kMethods) {
    bench::addBallScoreValues(prefix + "." + m.first, s.*m.second, values);
  }
  values->emplace_back(prefix + ".train_candidates", s.train_candidates);
  values->emplace_back(prefix + ".train_positives", s.train_positives);
  values->emplace_back(prefix + ".candidates", s.candidates);
  values->emplace_back(prefix + ".frames", s.range.frames);
  values->emplace_back(prefix + ".verify_us_per_candidate", s.candidates ? 1000.0 * s.verify_ms / s.candidates : 0);
}

// Every date held out in turn, `jobs` at a time (thread k on CPU k), in the dates' order.
std::vector<HeldOutScore> evaluateEach(const LoadedDates& loaded, const std::vector<Date>& dates, int label_class,
                                       int widen, bool compare_models, int jobs) {
  std::vector<HeldOutScore> scores(dates.size());
  std::vector<std::exception_ptr> failures(dates.size());
  std::atomic<size_t> next{0};
  const auto work = [&](int cpu) {
    if (jobs > 1) bench::pinToCpu(cpu);
    for (size_t i = next++; i < dates.size(); i = next++) {
      std::vector<const Date*> training;
      for (const Date& d : dates) {
        if (&d != &dates[i]) training.push_back(&d);
      }
      try {
        scores[i] = evaluate(loaded, dates[i], training, label_class, widen, compare_models);
      } catch (...) {
        failures[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> threads;
  for (int k = 1; k < jobs; ++k) threads.emplace_back(work, k);
  work(0);
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
  return scores;
}

void run(const std::vector<Date>& dates, int label_class, int widen, bool compare_models, int jobs,
         const std::string& json) {
  std::printf("rle_vision eval (ball verifier): each date held out, calibrated and trained on the others; "
              "candidates: the smallest range holding the ball as calibrated on each training date, widened by %d levels, the floor's colour first\n", widen);
  std::printf("%-10s %-46s %6s %7s %7s %6s %9s %8s\n", "held out", "method", "balls", "recall", "field-r", "blobs",
              "precision", "ms/frame");
  std::vector<std::pair<std::string, double>> values;
  const LoadedDates loaded = loadDates(dates, label_class);
  HeldOutScore all;
  std::map<std::string, double> worst;
  const std::vector<HeldOutScore> scores = evaluateEach(loaded, dates, label_class, widen, compare_models, jobs);
  for (size_t i = 0; i < dates.size(); ++i) {
    const Date& held_out = dates[i];
    const HeldOutScore& s = scores[i];
    std::fputs(s.log.c_str(), stdout);
    std::printf("%-10s floor guard scale chosen on the training dates: %.1f\n", held_out.name.c_str(), s.floor_guard_scale);
    values.emplace_back("dates." + held_out.name + ".floor_guard_scale", s.floor_guard_scale);
    for (size_t m = 0; m < kMethods.size(); ++m) printRow(held_out.name, kMethodNames[m], s.*kMethods[m].second);
    if (compare_models) {
      printRow(held_out.name, AlternativeModel::name(AlternativeModel::Kind::kSvm), s.svm);
      printRow(held_out.name, AlternativeModel::name(AlternativeModel::Kind::kMlp), s.mlp);
      printRow(held_out.name, AlternativeModel::name(AlternativeModel::Kind::kBoostWithField), s.boost_with_field);
    }
    addValues("dates." + held_out.name, s, &values);
    all.add(s);
    for (const auto& m : kMethods) {
      const BallScore& b = s.*m.second;
      for (const auto& f : {std::make_pair("precision_pct", b.precision()), std::make_pair("recall_pct", b.recall())}) {
        const std::string key = std::string("worst.") + m.first + "." + f.first;
        worst[key] = worst.count(key) ? std::min(worst[key], f.second) : f.second;
      }
    }
  }
  for (size_t m = 0; m < kMethods.size(); ++m) printRow("pooled", kMethodNames[m], all.*kMethods[m].second);
  if (compare_models) {
    printRow("pooled", AlternativeModel::name(AlternativeModel::Kind::kSvm), all.svm);
    printRow("pooled", AlternativeModel::name(AlternativeModel::Kind::kMlp), all.mlp);
    printRow("pooled", AlternativeModel::name(AlternativeModel::Kind::kBoostWithField), all.boost_with_field);
  }
  std::printf("verifier: %.1f us per candidate (features and score), %.1f candidates per frame\n",
              all.candidates ? 1000.0 * all.verify_ms / all.candidates : 0.0,
              all.range.frames ? static_cast<double>(all.candidates) / all.range.frames : 0.0);
  for (const auto& w : worst) std::printf("%-40s %6.1f\n", w.first.c_str(), w.second);
  addValues("pooled", all, &values);
  for (const auto& w : worst) values.emplace_back(w.first, w.second);
  values.emplace_back("widen_levels", widen);
  if (!json.empty()) bench::writeJson(json, values);
}

}  // namespace

int main(int argc, char** argv) {
  std::string root, json, label_class = "0", widen = "0", jobs = "1";
  bool compare_models = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--compare-models") {
      compare_models = true;
    } else if ((arg == "--json" || arg == "--label-class" || arg == "--widen" || arg == "--jobs") && i + 1 < argc) {
      (arg == "--json" ? json : arg == "--widen" ? widen : arg == "--jobs" ? jobs : label_class) = argv[++i];
    } else {
      root = arg;
    }
  }
  const std::vector<Date> dates = bench::labelledDates(root);
  const bool numbers =
      bench::isWholeNumber(label_class, 6) && bench::isWholeNumber(widen, 3) && bench::isWholeNumber(jobs, 3);
  if (dates.size() < 2 || !numbers) {
    std::cerr << "usage: rle_vision_eval_verifier [--label-class N] [--widen LEVELS] [--compare-models] [--jobs N] "
                 "[--json OUT] DIR (its folders: two or more dates)\n";
    return 2;
  }
  bench::pinToOneCpu();
  // No more threads than CPUs (each pinned to its own), nor than dates.
  const int cpus = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::clamp(std::stoi(jobs), 1, std::min(cpus, static_cast<int>(dates.size())));
  try {
    run(dates, std::stoi(label_class), std::stoi(widen), compare_models, threads, json);
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_eval_verifier: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
