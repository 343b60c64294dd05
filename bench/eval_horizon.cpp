// make eval (horizon): our landmark path against line-detector baselines on real labelled
// frames, in one run, one thread pinned to one CPU.
//
//   rle_vision_eval_horizon DIR... [--negatives DIR]... [--sim-frames N] [--params FILE]
//                           [--model FILE] [--json OUT] [--train-output FILE]
//
// DIR: labelled frames (label.csv: "filename,slope,offset", the horizon y = slope x + offset H,
// or with a has_horizon column; images in DIR/images/ or DIR/), grouped by flight
// (eval/horizon_data.h). --negatives: folders of frames without a horizon (indoor robot frames),
// grouped by their first sub-folder. --sim-frames: that many frames of the simulator's indoor
// scene (no horizon) and of its default scene (the true horizon) as two more groups.
//
// Our horizon's confidence is a model learned from the candidates' evidence: every group is
// scored with a model fitted without it (leave one group out: no frame is scored by a model
// that saw its flight, date or scene); that is the headline figure. Beside it: the shipped
// model (--model, default config/horizon_model.yaml: trained on everything here, in sample),
// the evidence product without a model, and the baselines' horizon, their longest segment
// within 45 deg of level (OpenCV FastLineDetector, LSD, Gauss + Canny + HoughLinesP). Per
// method: pass rate (angle error < 5 deg and Hesse distance error < 5% H; a frame without a
// horizon passes when nothing is reported), per group and the worst, found rate, errors over
// the frames with a horizon reported, the share of frames where a segment of 40 px or more
// lies on the true horizon, ms per frame. Then the robustness suite: the labelled frames again
// under perturbations (eval/horizon_data.h), ours held out against FastLineDetector.
// --train-output writes the model fitted on every group.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/fast_line_detector.hpp>

#include "eval/horizon_data.h"
#include "eval/horizon_metrics.h"
#include "harness.h"
#include "rle_vision/io/horizon_model_file.h"
#include "rle_vision/io/landmark_params_file.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"

namespace {

using namespace rle_vision;
using eval::HorizonFrame;

// The model's L2 penalties on standardised weights tried: each fit chooses one, with its
// threshold, by cross-validation over the groups it is fitted on.
constexpr double kL2Choices[] = {0.1, 1, 10, 100, 1000, 10000, 100000};
// The stop probabilities tried (HorizonModel::stop_probability): the candidates are weighed in
// order and the first at least this probable is taken; 2: every candidate weighed.
constexpr double kStopChoices[] = {0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999, 2};
const char* const kHeldOut = "ours, model held out (leave one group out)";
const char* const kShipped = "ours, shipped model (in sample)";
const char* const kProduct = "ours, evidence product (no model)";
const char* const kBaselines[] = {"FastLineDetector (longest level)", "LSD (longest level)", "HoughLinesP (longest level)"};

struct Segment4 {
  double x1, y1, x2, y2;
};

// What a method reports for one frame.
struct Detection {
  bool found = false;
  ImageLine horizon;
  std::vector<Segment4> segments;
  double ms = 0;
};

// One frame as analysed once: its truth, our lines and horizon candidates, the baselines.
struct FrameData {
  std::string dataset, group;
  bool has_horizon = false;
  ImageLine truth;
  int width = 0, height = 0;
  std::vector<HorizonEstimate> candidates;
  std::vector<int> candidate_passes;  // 1: the candidate is the true horizon
  std::vector<Segment4> our_segments;
  Detection product;
  double ours_ms = 0;  // the whole landmark step with the node's defaults (the shipped model)
  std::vector<Detection> baselines;
};

// The scores of one method over a set of frames.
struct Score {
  int frames = 0, passed = 0, found = 0, on_horizon = 0, horizon_frames = 0;
  std::vector<double> angle_errors, distance_errors, ms;
  std::map<std::string, std::pair<int, int>> groups;  // passed, frames
  void add(const FrameData& f, const Detection& d);
  double pct(int n) const { return frames ? 100.0 * n / frames : 0; }
};

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / v.size();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void Score::add(const FrameData& f, const Detection& d) {
  ++frames;
  ms.push_back(d.ms);
  found += d.found;
  bool pass = !d.found;
  if (f.has_horizon) {
    ++horizon_frames;
    for (const Segment4& s : d.segments) {
      if (eval::segmentOnHorizon(s.x1, s.y1, s.x2, s.y2, f.truth, f.height)) {
        ++on_horizon;
        break;
      }
    }
    pass = false;
    if (d.found) {
      const eval::HorizonError e = eval::horizonError(d.horizon, f.truth, f.width, f.height);
      angle_errors.push_back(e.angle_deg);
      distance_errors.push_back(e.distance_px);
      pass = eval::passes(e, f.height);
    }
  }
  passed += pass;
  auto& g = groups[f.group];
  g.first += pass;
  ++g.second;
}

// The longest segment within 45 deg of level, as a horizon.
Detection longestLevelSegment(std::vector<Segment4> segments, double ms) {
  Detection d;
  d.ms = ms;
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
  for (const Vec4& l : lines) out.push_back({double(l[0]), double(l[1]), double(l[2]), double(l[3])});
  return out;
}

template <typename Body>
double timeMs(Body body) {
  const auto start = std::chrono::steady_clock::now();
  body();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Everything each frame is run through (buffers kept across frames).
struct Methods {
  LandmarkOptions options;       // the node's defaults: with the shipped model when there is one
  LandmarkOptions no_model;      // the same without it (the candidates' evidence, the product)
  LandmarkDetector detector;
  HorizonDetector candidates;
  cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  cv::Mat gray;
};

std::vector<Detection> baselines(const cv::Mat& image, Methods& m, bool all) {
  std::vector<cv::Vec4f> fld_lines, lsd_lines;
  std::vector<cv::Vec4i> hough_lines;
  std::vector<Detection> out;
  double ms = timeMs([&] {
    cv::cvtColor(image, m.gray, cv::COLOR_BGR2GRAY);
    m.fld->detect(m.gray, fld_lines);
  });
  out.push_back(longestLevelSegment(toSegments(fld_lines), ms));
  if (!all) return out;
  ms = timeMs([&] {
    cv::cvtColor(image, m.gray, cv::COLOR_BGR2GRAY);
    m.lsd->detect(m.gray, lsd_lines);
  });
  out.push_back(longestLevelSegment(toSegments(lsd_lines), ms));
  ms = timeMs([&] {
    cv::Mat blurred, edges;
    cv::cvtColor(image, m.gray, cv::COLOR_BGR2GRAY);
    cv::GaussianBlur(m.gray, blurred, cv::Size(5, 5), 1.5);
    cv::Canny(blurred, edges, 30, 90);
    cv::HoughLinesP(edges, hough_lines, 1, CV_PI / 180, 40, 40, 5);
  });
  out.push_back(longestLevelSegment(toSegments(hough_lines), ms));
  return out;
}

// Our lines and every horizon candidate with its evidence, the product's choice, the baselines.
FrameData analyse(const cv::Mat& image, bool has_horizon, const ImageLine& truth, Methods& m, bool all_baselines) {
  FrameData f;
  f.has_horizon = has_horizon;
  f.truth = truth;
  f.width = image.cols;
  f.height = image.rows;
  LandmarkResult result;
  f.ours_ms = timeMs([&] { m.detector.detectInImage(image, m.options, &result); });
  LandmarkResult plain;
  const double product_ms = timeMs([&] { m.detector.detectInImage(image, m.no_model, &plain); });
  f.product.found = plain.horizon.found;
  f.product.horizon = plain.horizon.line;
  f.product.ms = product_ms;
  for (const DetectedLine& l : plain.lines) f.our_segments.push_back({l.x1, l.y1, l.x2, l.y2});
  f.product.segments = f.our_segments;
  f.candidates = m.candidates.candidates(image, m.detector.edges(), m.no_model.edge_gain, plain.lines, m.no_model.horizon);
  for (const HorizonEstimate& c : f.candidates) {
    f.candidate_passes.push_back(has_horizon && eval::passes(eval::horizonError(c.line, truth, f.width, f.height), f.height));
  }
  f.baselines = baselines(image, m, all_baselines);
  return f;
}

// The candidate `model` takes on a frame, as the detector does: the most probable, or the first
// reaching its stop probability (-1: none).
int chosenCandidate(const FrameData& f, const HorizonModel& model, double* probability) {
  int chosen = -1;
  *probability = -1;
  for (size_t i = 0; i < f.candidates.size(); ++i) {
    const double p = model.probability(f.candidates[i].features);
    if (p > *probability) *probability = p, chosen = static_cast<int>(i);
    if (p >= model.stop_probability) break;
  }
  return chosen;
}

// Our decision on a frame with `model`: its chosen candidate, found from min_confidence.
Detection decide(const FrameData& f, const HorizonModel& model, double min_confidence, double ms) {
  Detection d;
  d.ms = ms;
  d.segments = f.our_segments;
  double p = 0;
  const int chosen = chosenCandidate(f, model, &p);
  if (chosen >= 0) {
    d.horizon = f.candidates[chosen].line;
    d.found = p >= min_confidence;
  }
  return d;
}

// The model fitted on the candidates of the frames `use` accepts, each class weighing as much
// as the other, with L2 penalty `l2`.
template <typename Use>
HorizonModel fitOn(const std::vector<FrameData>& frames, Use use, double l2) {
  std::vector<HorizonFeatures> x;
  std::vector<int> y;
  for (const FrameData& f : frames) {
    if (!use(f)) continue;
    for (size_t i = 0; i < f.candidates.size(); ++i) {
      x.push_back(f.candidates[i].features);
      y.push_back(f.candidate_passes[i]);
    }
  }
  const double positives = static_cast<double>(std::count(y.begin(), y.end(), 1));
  const double negatives = static_cast<double>(y.size()) - positives;
  std::vector<double> w(y.size());
  for (size_t i = 0; i < y.size(); ++i) w[i] = 0.5 * y.size() / (y[i] ? std::max(positives, 1.0) : std::max(negatives, 1.0));
  return fitHorizonModel(x, y, w, l2);
}

// A frame as an inner fold scored it: its best candidate's probability and whether that
// candidate is the horizon.
struct InnerScore {
  const FrameData* frame;
  double best;
  int pass;
};

// The inner folds over the frames `use` accepts: per group, `fit(in_fold)` fitted on the other
// groups' frames, then `visit(frame, model)` on each frame of the group.
template <typename Use, typename Fit, typename Visit>
void forEachInnerFold(const std::vector<FrameData>& frames, Use use, Fit fit, Visit visit) {
  std::set<std::string> groups;
  for (const FrameData& f : frames) {
    if (use(f)) groups.insert(f.group);
  }
  for (const std::string& g : groups) {
    HorizonModel model = fit([&](const FrameData& f) { return use(f) && f.group != g; });
    for (const FrameData& f : frames) {
      if (use(f) && f.group == g) visit(f, model);
    }
  }
}

// The frames `use` accepts, each group scored by a model (penalty `l2`) fitted without it.
template <typename Use>
std::vector<InnerScore> innerScores(const std::vector<FrameData>& frames, Use use, double l2) {
  std::vector<InnerScore> scored;
  forEachInnerFold(
      frames, use, [&](auto in_fold) { return fitOn(frames, in_fold, l2); },
      [&](const FrameData& f, const HorizonModel& model) {
        double p = 0;
        const int chosen = chosenCandidate(f, model, &p);  // the model weighs every candidate
        scored.push_back(chosen >= 0 ? InnerScore{&f, p, f.candidate_passes[chosen]} : InnerScore{&f, 0, 0});
      });
  return scored;
}

// Frame errors at threshold t, horizon frames and frames without one weighing alike.
double frameErrorCost(const std::vector<InnerScore>& scored, double t) {
  double with = 0, without = 0, missed = 0, false_found = 0;
  for (const InnerScore& s : scored) {
    const bool found = s.best >= t;
    if (s.frame->has_horizon) {
      ++with;
      missed += !(found && s.pass);
    } else {
      ++without;
      false_found += found;
    }
  }
  return missed / std::max(with, 1.0) + false_found / std::max(without, 1.0);
}

struct ModelChoice {
  double l2 = 1, threshold = 0.5, stop = 2;
};

// The L2 penalty and decision threshold for the frames `use` accepts: each group scored by a
// model fitted without it (nested inside any outer hold-out), the pair with the fewest frame
// errors (ties: the stronger penalty, the simpler model; then the threshold nearest 0.5).
template <typename Use>
ModelChoice chooseModel(const std::vector<FrameData>& frames, Use use) {
  ModelChoice best;
  double best_cost = INFINITY;
  for (const double l2 : kL2Choices) {
    const std::vector<InnerScore> scored = innerScores(frames, use, l2);
    for (int k = 1; k < 20; ++k) {
      const double t = 0.05 * k, cost = frameErrorCost(scored, t);
      const bool tie = std::fabs(cost - best_cost) <= 1e-12;
      if (cost < best_cost - 1e-12 || (tie && l2 > best.l2) ||
          (tie && l2 == best.l2 && std::fabs(t - 0.5) < std::fabs(best.threshold - 0.5))) {
        best_cost = cost;
        best = {l2, t};
      }
    }
  }
  return best;
}

// The model for the frames `use` accepts with penalty and threshold `choice`, the threshold
// moved into the bias so that it decides at probability 0.5.
template <typename Use>
HorizonModel fitChosen(const std::vector<FrameData>& frames, Use use, const ModelChoice& choice) {
  HorizonModel model = fitOn(frames, use, choice.l2);
  model.bias -= std::log(choice.threshold / (1 - choice.threshold));
  return model;
}

// The stop probability for the frames `use` accepts: each group decided by a model of `choice`
// fitted without it, the stop that gets the most frames right (a horizon found and passing, or
// none found where there is none); of equals, the highest (weighing every candidate, when no
// stop does better).
template <typename Use>
double chooseStop(const std::vector<FrameData>& frames, Use use, const ModelChoice& choice) {
  constexpr size_t kStops = std::size(kStopChoices);
  std::array<int, kStops> right{};
  forEachInnerFold(
      frames, use, [&](auto in_fold) { return fitChosen(frames, in_fold, choice); },
      [&](const FrameData& f, HorizonModel& model) {
        for (size_t k = 0; k < kStops; ++k) {
          model.stop_probability = kStopChoices[k];
          double p = 0;
          const int chosen = chosenCandidate(f, model, &p);
          const bool found = chosen >= 0 && p >= 0.5;  // fitChosen's model decides at 0.5
          right[k] += f.has_horizon ? found && f.candidate_passes[chosen] : !found;
        }
      });
  size_t best = kStops - 1;  // ties: the higher stop, nearer weighing every candidate
  for (size_t k = kStops - 1; k-- > 0;) {
    if (right[k] > right[best]) best = k;
  }
  return kStopChoices[best];
}

// The model for the frames outside `held_out` ("": every frame), its penalty, decision
// threshold and stop probability chosen by the inner cross-validation.
HorizonModel fitWithout(const std::vector<FrameData>& frames, const std::string& held_out, ModelChoice* chosen = nullptr) {
  auto use = [&](const FrameData& f) { return held_out.empty() || f.group != held_out; };
  ModelChoice choice = chooseModel(frames, use);
  choice.stop = chooseStop(frames, use, choice);
  HorizonModel model = fitChosen(frames, use, choice);
  model.stop_probability = choice.stop;
  if (chosen) *chosen = choice;
  return model;
}

std::map<std::string, HorizonModel> heldOutModels(const std::vector<FrameData>& frames) {
  std::map<std::string, HorizonModel> models;
  std::printf("held-out models' L2 penalty / threshold / stop probability, chosen without the group:");
  for (const FrameData& f : frames) {
    if (models.count(f.group)) continue;
    ModelChoice choice;
    models[f.group] = fitWithout(frames, f.group, &choice);
    std::printf(" %s %g/%.2f/%g", f.group.c_str(), choice.l2, choice.threshold, choice.stop);
  }
  std::printf("\n");
  return models;
}

}  // namespace

#include "eval_horizon_report.h"

int main(int argc, char** argv) {
  EvalArguments args;
  if (!parseArguments(argc, argv, &args)) return 2;
  bench::pinToOneCpu();
  cv::setNumThreads(1);
  Methods methods;
  std::vector<HorizonFrame> sources;
  if (!loadSetup(args, &methods, &sources)) return 2;
  std::vector<FrameData> frames = analyseAll(sources, args, methods);
  if (frames.empty()) {
    std::cerr << "rle_vision_eval_horizon: no frames could be read\n";
    return 2;
  }
  const std::map<std::string, HorizonModel> held_out = heldOutModels(frames);
  const Results results = scoreAll(frames, held_out, methods);
  const std::vector<RobustnessRow> robustness = runRobustness(sources, held_out, methods);
  report(args, frames, results, robustness);
  if (!args.train_output.empty()) writeModel(args, frames);
  return 0;
}
