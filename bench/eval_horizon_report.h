// rle_vision_eval_horizon's set-up, scoring and report (included by eval_horizon.cpp after its
// frame analysis).
#pragma once

namespace {

struct EvalArguments {
  std::vector<std::string> labelled, negatives;
  int sim_frames = 0;
  std::string params_file, model_file, json_path, train_output;
  std::string source_dir = RLE_VISION_SOURCE_DIR;
};

bool parseArguments(int argc, char** argv, EvalArguments* a) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--negatives" && has_value) {
      a->negatives.push_back(argv[++i]);
    } else if (arg == "--sim-frames" && has_value) {
      a->sim_frames = std::max(0, std::atoi(argv[++i]));
    } else if (arg == "--params" && has_value) {
      a->params_file = argv[++i];
    } else if (arg == "--model" && has_value) {
      a->model_file = argv[++i];
    } else if (arg == "--json" && has_value) {
      a->json_path = argv[++i];
    } else if (arg == "--train-output" && has_value) {
      a->train_output = argv[++i];
    } else if (arg.rfind("--", 0) == 0) {
      std::cerr << "rle_vision_eval_horizon: unknown option " << arg << "\n";
      return false;
    } else {
      a->labelled.push_back(arg);
    }
  }
  if (a->labelled.empty()) {
    std::cerr << "usage: rle_vision_eval_horizon DIR... [--negatives DIR]... [--sim-frames N] [--params FILE] "
                 "[--model FILE] [--json OUT] [--train-output FILE]\n";
    return false;
  }
  if (a->model_file.empty()) a->model_file = a->source_dir + "/config/horizon_model.yaml";
  return true;
}

bool loadSetup(const EvalArguments& a, Methods* m, std::vector<HorizonFrame>* sources) {
  try {
    if (!a.params_file.empty()) m->options = loadLandmarkParams(a.params_file);
    m->no_model = m->options;
    if (std::ifstream(a.model_file).good()) {
      try {
        m->options.horizon.model = loadHorizonModel(a.model_file);
      } catch (const std::exception& e) {
        // A model of an older feature set must not stop the fit that replaces it.
        if (a.train_output.empty()) throw;
        std::cerr << "rle_vision_eval_horizon: " << e.what() << " (ignored: --train-output writes a new one)\n";
      }
    }
    for (const std::string& dir : a.labelled) {
      const std::vector<HorizonFrame> f = eval::labelledFrames(dir);
      sources->insert(sources->end(), f.begin(), f.end());
    }
    eval::mergeCutFlights(sources);
    for (const std::string& dir : a.negatives) {
      const std::vector<HorizonFrame> f = eval::framesWithoutHorizon(dir);
      sources->insert(sources->end(), f.begin(), f.end());
    }
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_eval_horizon: " << e.what() << "\n";
    return false;
  }
  return true;
}

// The simulator's frames: the indoor scene (no horizon) and the default scene (its horizon).
void analyseSimulator(int count, const std::string& source_dir, Methods& m, std::vector<FrameData>* frames) {
  for (const char* scene : {"scene_indoor", "scene_default"}) {
    const SceneSimulator simulator(loadSceneConfig(source_dir + "/config/" + scene + ".yaml"));
    for (int i = 0; i < count; ++i) {
      const SimFrame frame = simulator.render(11 * i, 11 * i / 30.0);
      FrameData f = analyse(frame.image, frame.horizon_visible, frame.horizon, m, true);
      f.dataset = std::string("simulator ") + scene;
      f.group = f.dataset;
      frames->push_back(std::move(f));
    }
  }
}

std::vector<FrameData> analyseAll(const std::vector<HorizonFrame>& sources, const EvalArguments& a, Methods& m) {
  std::vector<FrameData> frames;
  for (const HorizonFrame& source : sources) {
    const cv::Mat image = cv::imread(source.path, cv::IMREAD_COLOR);
    if (image.empty()) {
      std::cerr << "rle_vision_eval_horizon: cannot read " << source.path << " (skipped)\n";
      continue;
    }
    const ImageLine truth = source.label.has_horizon ? source.label.line(image.rows) : ImageLine();
    FrameData f = analyse(image, source.label.has_horizon, truth, m, true);
    f.dataset = source.dataset;
    f.group = source.group;
    frames.push_back(std::move(f));
  }
  if (a.sim_frames > 0) analyseSimulator(a.sim_frames, a.source_dir, m, &frames);
  return frames;
}

// Scores per method: over every frame with a horizon ("horizon frames", the pooled figure),
// per data set, and per data set without one.
struct Results {
  std::vector<std::string> methods;
  std::map<std::string, Score> horizon;                        // method -> over frames with a horizon
  std::map<std::string, std::map<std::string, Score>> datasets;  // dataset -> method -> score
};

void listFrame(const FrameData& f, const HorizonModel& model, double min_confidence) {
  const Detection d = decide(f, model, min_confidence, 0);
  bool pass = !d.found;
  double angle = -1, distance = -1;
  if (f.has_horizon && d.found) {
    const eval::HorizonError e = eval::horizonError(d.horizon, f.truth, f.width, f.height);
    angle = e.angle_deg, distance = e.distance_px, pass = eval::passes(e, f.height);
  } else if (f.has_horizon) {
    pass = false;
  }
  std::printf("frame %s %s horizon %d found %d pass %d angle %.1f dist %.1f truth th=%.1f c=%.1f cands:", f.dataset.c_str(),
              f.group.c_str(), f.has_horizon, d.found, pass, angle, distance, f.truth.theta * 180 / M_PI, f.truth.intercept);
  for (size_t i = 0; i < f.candidates.size(); ++i) {
    std::printf(" [%d p=%.2f prod=%.2f th=%.1f c=%.1f]", f.candidate_passes[i], model.probability(f.candidates[i].features),
                f.candidates[i].confidence, f.candidates[i].line.theta * 180 / M_PI, f.candidates[i].line.intercept);
    if (std::getenv("EVAL_HORIZON_FEATURES")) {
      std::printf("{");
      for (int k = 0; k < kHorizonFeatureCount; ++k) std::printf("%s%.2f", k ? " " : "", f.candidates[i].features[k]);
      std::printf("}");
    }
  }
  std::printf("\n");
}

Results scoreAll(const std::vector<FrameData>& frames, const std::map<std::string, HorizonModel>& held_out, const Methods& m) {
  Results r;
  r.methods = {kHeldOut, kShipped, kProduct, kBaselines[0], kBaselines[1], kBaselines[2]};
  const double min_confidence = m.options.horizon.min_confidence;
  const bool list = std::getenv("EVAL_HORIZON_LIST") != nullptr;  // development: every frame's held-out decision
  for (const FrameData& f : frames) {
    if (list) listFrame(f, held_out.at(f.group), min_confidence);
    std::vector<Detection> d = {decide(f, held_out.at(f.group), min_confidence, f.ours_ms),
                                m.options.horizon.model.valid ? decide(f, m.options.horizon.model, min_confidence, f.ours_ms)
                                                              : f.product,
                                f.product, f.baselines[0], f.baselines[1], f.baselines[2]};
    for (size_t k = 0; k < r.methods.size(); ++k) {
      if (f.has_horizon && f.dataset.rfind("simulator", 0) != 0) r.horizon[r.methods[k]].add(f, d[k]);
      r.datasets[f.dataset][r.methods[k]].add(f, d[k]);
    }
  }
  return r;
}

struct RobustnessRow {
  std::string name;
  Score ours, fld;
};

// The labelled frames again under each perturbation: ours with the model held out from the
// frame's flight, against FastLineDetector's longest level segment.
std::vector<RobustnessRow> runRobustness(const std::vector<HorizonFrame>& sources,
                                         const std::map<std::string, HorizonModel>& held_out, Methods& m) {
  std::vector<RobustnessRow> rows;
  for (const eval::Perturbation& p : eval::robustnessSuite()) rows.push_back({p.name, Score(), Score()});
  uint64_t seed = 1;
  for (const HorizonFrame& source : sources) {
    if (!source.label.has_horizon || !held_out.count(source.group)) continue;
    const cv::Mat image = cv::imread(source.path, cv::IMREAD_COLOR);
    if (image.empty()) continue;
    const std::vector<eval::Perturbation> suite = eval::robustnessSuite();
    for (size_t k = 0; k < suite.size(); ++k) {
      ImageLine truth = source.label.line(image.rows);
      const cv::Mat perturbed = eval::perturb(image, suite[k], seed++, &truth);
      FrameData f = analyse(perturbed, true, truth, m, false);
      f.group = source.group;
      f.dataset = suite[k].name;
      if (std::getenv("EVAL_HORIZON_LIST")) listFrame(f, held_out.at(source.group), m.options.horizon.min_confidence);
      rows[k].ours.add(f, decide(f, held_out.at(source.group), m.options.horizon.min_confidence, f.product.ms));
      rows[k].fld.add(f, f.baselines[0]);
    }
  }
  return rows;
}

// The group with the lowest pass rate.
std::pair<std::string, double> worstGroup(const Score& s) {
  std::pair<std::string, double> worst{"-", 100.0};
  for (const auto& g : s.groups) {
    const double pct = 100.0 * g.second.first / std::max(1, g.second.second);
    if (pct < worst.second) worst = {g.first, pct};
  }
  return worst;
}

std::string scoreJson(const Score& s, bool line_detector) {
  std::ostringstream j;
  const auto worst = worstGroup(s);
  j << "{\"frames\": " << s.frames << ", \"pass_pct\": " << s.pct(s.passed) << ", \"found_pct\": " << s.pct(s.found)
    << ", \"angle_error_mean_deg\": " << mean(s.angle_errors) << ", \"angle_error_median_deg\": " << median(s.angle_errors)
    << ", \"distance_error_mean_px\": " << mean(s.distance_errors)
    << ", \"on_horizon_pct\": " << (line_detector && s.horizon_frames ? 100.0 * s.on_horizon / s.horizon_frames : -1)
    << ", \"ms_per_frame\": " << mean(s.ms) << ", \"worst_group\": \"" << worst.first
    << "\", \"worst_group_pass_pct\": " << worst.second << ", \"groups\": {";
  bool first = true;
  for (const auto& g : s.groups) {
    j << (first ? "" : ", ") << "\"" << g.first << "\": " << 100.0 * g.second.first / std::max(1, g.second.second);
    first = false;
  }
  j << "}}";
  return j.str();
}

void printScores(const char* title, const std::vector<std::string>& methods, const std::map<std::string, Score>& scores) {
  std::printf("\n%s\n%-44s %6s %6s %6s %8s %8s %9s %8s %s\n", title, "method", "frames", "pass%", "found%", "angle", "angle",
              "dist px", "ms", "worst group");
  std::printf("%-44s %6s %6s %6s %8s %8s %9s %8s\n", "", "", "", "", "mean deg", "med deg", "mean", "mean");
  for (const std::string& name : methods) {
    if (!scores.count(name)) continue;
    const Score& s = scores.at(name);
    const auto worst = worstGroup(s);
    std::printf("%-44s %6d %6.1f %6.1f %8.2f %8.2f %9.1f %8.2f %s %.1f%%\n", name.c_str(), s.frames, s.pct(s.passed),
                s.pct(s.found), mean(s.angle_errors), median(s.angle_errors), mean(s.distance_errors), mean(s.ms),
                worst.first.c_str(), worst.second);
  }
}

void report(const EvalArguments& a, const std::vector<FrameData>& frames, const Results& r,
            const std::vector<RobustnessRow>& robustness) {
  std::printf("rle_vision eval (horizon): %zu frames; one thread pinned to one CPU. Pass: angle error < %.0f deg and "
              "Hesse distance error < %.0f%% of H; a frame without a horizon passes when none is reported. The model "
              "held out: every group (flight, date, scene) scored by a model fitted without it.\n",
              frames.size(), eval::kPassAngleDeg, 100 * eval::kPassDistanceShareOfHeight);
  printScores("all labelled frames with a horizon (pooled):", r.methods, r.horizon);
  for (const auto& d : r.datasets) printScores(("data set " + d.first + ":").c_str(), r.methods, d.second);
  std::printf("\nrobustness suite (labelled frames perturbed): pass %%, ours held out / FastLineDetector\n");
  for (const RobustnessRow& row : robustness) {
    std::printf("  %-20s %6.1f / %6.1f   (%d frames)\n", row.name.c_str(), row.ours.pct(row.ours.passed),
                row.fld.pct(row.fld.passed), row.ours.frames);
  }
  if (a.json_path.empty()) return;
  std::ostringstream j;
  j << "{\n  \"machine\": \"" << bench::machineName() << "\",\n  \"date\": \"" << bench::todayUtc() << "\",\n  \"frames\": "
    << r.horizon.at(kHeldOut).frames << ",\n  \"methods\": {";
  for (size_t k = 0; k < r.methods.size(); ++k) {
    j << (k ? "," : "") << "\n    \"" << r.methods[k] << "\": " << scoreJson(r.horizon.at(r.methods[k]), true);
  }
  j << "\n  },\n  \"datasets\": {";
  bool first = true;
  for (const auto& d : r.datasets) {
    j << (first ? "" : ",") << "\n    \"" << d.first << "\": {";
    for (size_t k = 0; k < r.methods.size(); ++k) {
      j << (k ? ", " : "") << "\"" << r.methods[k] << "\": " << scoreJson(d.second.at(r.methods[k]), true);
    }
    j << "}";
    first = false;
  }
  j << "\n  },\n  \"robustness\": {";
  for (size_t k = 0; k < robustness.size(); ++k) {
    j << (k ? "," : "") << "\n    \"" << robustness[k].name << "\": {\"frames\": " << robustness[k].ours.frames
      << ", \"pass_pct\": " << robustness[k].ours.pct(robustness[k].ours.passed)
      << ", \"fld_pass_pct\": " << robustness[k].fld.pct(robustness[k].fld.passed) << "}";
  }
  j << "\n  }\n}\n";
  std::ofstream(a.json_path) << j.str();
  std::printf("wrote %s\n", a.json_path.c_str());
}

void writeModel(const EvalArguments& a, const std::vector<FrameData>& frames) {
  ModelChoice choice;
  const HorizonModel model = fitWithout(frames, "", &choice);
  std::set<std::string> sets;
  for (const FrameData& f : frames) sets.insert(f.dataset + " (" + std::to_string(std::count_if(frames.begin(), frames.end(),
                                                    [&](const FrameData& g) { return g.dataset == f.dataset; })) + ")");
  std::string provenance =
      "The horizon model of rle_vision (see include/rle_vision/landmark/horizon_model.h): a logistic regression\n"
      "over the evidence of every candidate line, fitted (L2 " + cv::format("%g", choice.l2) +
      " on standardised weights, threshold " + cv::format("%.2f", choice.threshold) + " and stop probability " +
      cv::format("%g", choice.stop) + ", all chosen by\n"
      "leave-one-group-out cross-validation; each class weighing as much as the other) by `make train-horizon` on the frames of:\n";
  for (const std::string& s : sets) provenance += "  " + s + "\n";
  provenance += "Held-out figures (each flight, date or scene scored by a model fitted without it): make eval.";
  std::ofstream(a.train_output) << horizonModelYaml(model, provenance);
  std::printf("wrote the model fitted on every frame to %s\n", a.train_output.c_str());
}

}  // namespace
