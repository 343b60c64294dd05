// rle_vision_train: a verifier for a colour class from labelled frames (verify/blob_verifier.h).
// Each FOLDER is a group (a recording, a date: one hall's light). The class is calibrated on each
// group's labelled boxes (rle_vision_calibrate's core); the candidates' range is the smallest
// holding all of them (optionally widened); its blobs, with the floor's colour taking the floor's
// pixels first as in the tracker, are the candidates; those on a labelled box are the positives.
// The floor's range grown by a scale takes the floor's pixels first (the tracker's floor_guard
// class): the scale is chosen among floorGuardScalesTried() by grouped cross-validation (each
// folder held out in turn) and kept in the file. With two or more groups the verifier is one
// model per group, trained without it (a candidate scores their mean), and every group is held
// out in turn: a range, a floor guard scale and a verifier made from the others score its candidates.
//
//   rle_vision_train --class NAME --label-class N [--widen LEVELS] --output FILE FOLDER...
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "rle_vision/field/field_detector.h"
#include "rle_vision/io/yolo_labels.h"
#include "rle_vision/learning/color_calibration.h"
#include "rle_vision/verify/blob_verifier.h"
#include "rle_vision/verify/verifier_training.h"

namespace {

using namespace rle_vision;

const char* kUsage =
    "usage: rle_vision_train --class NAME --label-class N [--widen LEVELS] --output FILE FOLDER...\n"
    "  --class NAME       the class the verifier is for (the colour class of that name)\n"
    "  --label-class N    its boxes: class N of the YOLO label file beside each image\n"
    "  --widen LEVELS     widen the candidates' range (the smallest holding the class as calibrated in each FOLDER)\n"
    "                     by this on every channel (default 0)\n"
    "  --output FILE      the verifier (YAML: the model and the candidates' range)\n"
    "  FOLDER             images with labels (and the folders below it); each FOLDER is a group held out in turn\n"
    "Exit status: 0 done, 2 bad input (no images, unreadable files, no labelled object among the candidates).\n";

struct Arguments {
  std::string name, output;
  int label_class = -1, widen = 0;
  std::vector<std::string> folders;
};

bool wholeNumber(const std::string& text, int max_digits) {
  return !text.empty() && text.size() <= static_cast<size_t>(max_digits) &&
         text.find_first_not_of("0123456789") == std::string::npos;
}

bool parse(int argc, char** argv, Arguments* a) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool valued = arg == "--class" || arg == "--label-class" || arg == "--widen" || arg == "--output";
    if (valued && i + 1 >= argc) return false;
    if (arg == "--class") {
      a->name = argv[++i];
    } else if (arg == "--output") {
      a->output = argv[++i];
    } else if (arg == "--label-class" || arg == "--widen") {
      const std::string value = argv[++i];
      if (!wholeNumber(value, arg == "--widen" ? 3 : 6)) return false;
      (arg == "--widen" ? a->widen : a->label_class) = std::stoi(value);
    } else if (!arg.empty() && arg[0] == '-') {
      return false;
    } else {
      a->folders.push_back(arg);
    }
  }
  return !a->name.empty() && !a->output.empty() && a->label_class >= 0 && a->widen <= 255 && !a->folders.empty();
}

// Candidate-level figures of `verifier` on `set`: recall of the positives, precision of the kept.
// Printed, and returned (for the model file's note).
std::string printScores(const std::string& what, const BlobVerifier& verifier, const VerifierTrainingSet& set) {
  int kept = 0, kept_positive = 0;
  for (int i = 0; i < set.features().rows; ++i) {
    CandidateFeatures x;
    std::copy(set.features().ptr<float>(i), set.features().ptr<float>(i) + kCandidateFeatureCount, x.begin());
    if (verifier.score(x) < 0.5f) continue;
    ++kept;
    kept_positive += set.labels()[i];
  }
  const int positives = set.positives();
  char line[512];
  std::snprintf(line, sizeof(line), "%-28s candidates %6d, on the object %5d: kept %5d, recall %5.1f%%, precision %5.1f%%",
                what.c_str(), set.features().rows, positives, kept, positives ? 100.0 * kept_positive / positives : 0.0,
                kept ? 100.0 * kept_positive / kept : 100.0);
  std::printf("%s\n", line);
  return line;
}

std::string folderName(const std::string& folder) {
  const std::string trimmed = folder.substr(0, folder.find_last_not_of('/') + 1);
  return trimmed.substr(trimmed.find_last_of('/') + 1);
}

using Groups = std::vector<std::vector<std::string>>;
constexpr size_t kNone = static_cast<size_t>(-1);

// The candidates' range: the smallest holding the class as calibrated on each group's labelled
// boxes (all groups but `skip`; a group without any adds nothing), widened.
ColorClass candidateRange(const Arguments& a, const Groups& groups, size_t skip) {
  std::vector<ColorClass> calibrated;
  for (size_t g = 0; g < groups.size(); ++g) {
    if (g == skip) continue;
    std::vector<CalibrationExample> examples;
    for (const std::string& path : groups[g]) {
      CalibrationExample e = readYoloExample(path, a.label_class);
      if (!e.boxes.empty()) examples.push_back(std::move(e));
    }
    if (!examples.empty()) calibrated.push_back(calibrateColorClass(examples, a.name).color_class);
  }
  if (calibrated.empty()) {
    throw std::runtime_error("no box of label class " + std::to_string(a.label_class) + " in any label file");
  }
  return widenedRange(rangeCovering(calibrated), a.widen);
}

// The candidates of the frames of `groups` (only group `only`, or all but `skip`), one set per
// floor guard scale in `scales`: each frame read, and its floor found, once.
std::vector<VerifierTrainingSet> candidates(const Arguments& a, const Groups& groups, const ColorClass& range,
                                            const std::vector<double>& scales, size_t skip, size_t only = kNone) {
  std::vector<VerifierTrainingSet> sets;
  for (double scale : scales) sets.emplace_back(range, 20, scale);
  for (size_t g = 0; g < groups.size(); ++g) {
    if (g == skip || (only != kNone && g != only)) continue;
    for (VerifierTrainingSet& set : sets) set.setGroup(static_cast<int>(g));
    for (const std::string& path : groups[g]) {
      const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
      if (bgr.empty()) throw std::runtime_error(path + ": cannot read the image");
      FieldResult field;
      FieldDetector().detect(bgr, &field);
      const std::vector<cv::Rect> boxes = readYoloBoxes(yoloLabelPath(path), a.label_class, bgr.size());
      for (VerifierTrainingSet& set : sets) set.addFrame(bgr, boxes, field.colour.found ? &field.colour.range : nullptr);
    }
  }
  return sets;
}

// The floor guard's scale chosen on `sets` (chooseFloorGuardScale), printed with each scale's
// held-out F1 (`indent` before each line); returns the index of its set.
size_t chosenScale(const std::vector<VerifierTrainingSet>& sets, const std::string& indent, std::string* note) {
  std::vector<double> f1;
  const double scale = chooseFloorGuardScale(sets, &f1);
  if (distinctGroups(sets[0].groups()).size() < 2) {
    char line[160];
    std::snprintf(line, sizeof(line), "%sfloor guard scale %.1f: one folder, none held out to choose another", indent.c_str(), scale);
    std::printf("%s\n", line);
    if (note) *note += std::string(line) + "\n";
    return 0;
  }
  size_t chosen = 0;
  for (size_t k = 0; k < sets.size(); ++k) {
    if (sets[k].floorGuardScale() == scale) chosen = k;
    char line[160];
    std::snprintf(line, sizeof(line), "%sfloor guard scale %.1f: held-out mean F1 %.3f%s", indent.c_str(),
                  sets[k].floorGuardScale(), f1[k], sets[k].floorGuardScale() == scale ? " (chosen)" : "");
    std::printf("%s\n", line);
    if (note) *note += std::string(line) + "\n";
  }
  return chosen;
}

// Each folder held out: its range, its floor guard's scale and its verifier come from the other
// folders only; its candidates scored. The lines go to the model file's note too.
void printHeldOut(const Arguments& a, const Groups& groups, std::string* note) {
  for (size_t held = 0; held < groups.size() && groups.size() > 1; ++held) {
    const ColorClass held_range = candidateRange(a, groups, held);
    const std::vector<VerifierTrainingSet> others = candidates(a, groups, held_range, floorGuardScalesTried(), held);
    std::printf("held out %s: the floor guard's scale chosen on the other folders\n", folderName(a.folders[held]).c_str());
    const VerifierTrainingSet& chosen = others[chosenScale(others, "  ", nullptr)];
    if (chosen.positives() == 0 || chosen.positives() == static_cast<int>(chosen.labels().size())) continue;
    const VerifierTrainingSet held_set = candidates(a, groups, held_range, {chosen.floorGuardScale()}, kNone, held)[0];
    char what[96];
    std::snprintf(what, sizeof(what), "held out %s (scale %.1f)", folderName(a.folders[held]).c_str(), chosen.floorGuardScale());
    *note += printScores(what,
                         BlobVerifier::trainAcrossGroups(chosen.features(), chosen.labels(), chosen.groups()), held_set) +
             "\n";
  }
}

int run(const Arguments& a) {
  Groups groups;
  for (const std::string& folder : a.folders) {
    groups.push_back(imagesUnderFolder(folder));
    if (groups.back().empty()) throw std::runtime_error(folder + ": no .jpg, .jpeg or .png images in it or below it");
  }
  const ColorClass range = candidateRange(a, groups, kNone);
  const std::vector<VerifierTrainingSet> by_scale = candidates(a, groups, range, floorGuardScalesTried(), kNone);
  if (by_scale[0].positives() == 0) {
    throw std::runtime_error("no candidate lies on a labelled " + a.name + ": check --label-class and --widen");
  }
  std::printf("candidates: %s YUV [%d %d %d]..[%d %d %d] (calibrated per folder, covered, widened by %d)\n", a.name.c_str(), range.min[0],
              range.min[1], range.min[2], range.max[0], range.max[1], range.max[2], a.widen);
  // How the file was made, kept in it: the command, the data, the held-out figures.
  std::string note = "Made by rle_vision_train --class " + a.name + " --label-class " + std::to_string(a.label_class) +
                     " --widen " + std::to_string(a.widen) + " from the folders";
  size_t frames = 0;
  for (size_t g = 0; g < groups.size(); ++g) {
    note += " " + folderName(a.folders[g]);
    frames += groups[g].size();
  }
  note += " (" + std::to_string(frames) + " frames).\nThe floor guard's scale (the floor's range grown about its centre), "
          "chosen by grouped cross-validation (each folder held out in turn):\n";
  const VerifierTrainingSet& all = by_scale[chosenScale(by_scale, "", &note)];
  note += "Candidate-level figures, 0.5 the threshold:\n";
  printHeldOut(a, groups, &note);
  BlobVerifier verifier = BlobVerifier::trainAcrossGroups(all.features(), all.labels(), all.groups());
  verifier.setCandidateRange(range);
  verifier.setFloorGuardScale(all.floorGuardScale());
  note += std::to_string(verifier.modelCount()) + (verifier.modelCount() > 1 ? " models, one per folder, each trained without it; a "
                                                                              "candidate scores their mean\n"
                                                                            : " model\n");
  note += printScores("training (all folders)", verifier, all);
  verifier.save(a.output, note);
  std::printf("wrote %s (floor guard scale %.1f)\n", a.output.c_str(), all.floorGuardScale());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (!parse(argc, argv, &args)) {
    std::cerr << kUsage;
    return 2;
  }
  try {
    return run(args);
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_train: " << e.what() << "\n";
    return 2;
  }
}
