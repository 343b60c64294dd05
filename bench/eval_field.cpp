// make eval (field boundary): on labelled robot frames, how often the field boundary is found and
// how many labelled objects standing on the field (balls, robots, people's feet: each box's
// bottom centre) it puts on the field side, per recording date (a date is one hall and light:
// the grouping make eval reports its worst of). Each frame stands alone: the field colour is
// seeded on it, nothing is tuned on these frames.
//
//   rle_vision_eval_field [--margin-px N] [--json OUT] DIR
//
// DIR's folders are the dates; each holds folders of images with YOLO label files beside them
// (classes 0 ball, 1 obstacle, 2 human, as robocup_ml's obj.names).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "harness.h"
#include "rle_vision/field/field_detector.h"
#include "rle_vision/io/yolo_labels.h"

namespace {

using namespace rle_vision;

const char* const kClasses[] = {"ball", "obstacle", "human"};
constexpr int kClassCount = 3;

struct Count {
  int objects = 0, on_field = 0;
  double pct() const { return objects ? 100.0 * on_field / objects : 100.0; }
};

struct DateScore {
  int frames = 0, found = 0;
  double ms = 0;
  Count classes[kClassCount];
  double foundPct() const { return frames ? 100.0 * found / frames : 0; }
};

// One frame: the boundary, and each labelled object's bottom centre against it.
void scoreFrame(const std::string& path, double margin_px, DateScore* s) {
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) return;
  FieldDetector detector;  // seeded on this frame alone
  FieldResult field;
  detector.detect(image, &field);
  ++s->frames;
  s->ms += field.ms;
  if (!field.boundary.found) return;
  ++s->found;
  for (int c = 0; c < kClassCount; ++c) {
    for (const cv::Rect& box : readYoloBoxes(yoloLabelPath(path), c, image.size())) {
      const double above = field.boundary.heightAbove(box.x + 0.5 * box.width, box.y + box.height - 1);
      ++s->classes[c].objects;
      s->classes[c].on_field += above <= margin_px;
    }
  }
}

void printRow(const std::string& name, const DateScore& s) {
  std::printf("%-22s %6d %7.1f %7.2f", name.c_str(), s.frames, s.foundPct(), s.frames ? s.ms / s.frames : 0.0);
  for (const Count& c : s.classes) std::printf("   %5.1f%% of %4d", c.pct(), c.objects);
  std::printf("\n");
}

void addValues(const std::string& key, const DateScore& s, std::vector<std::pair<std::string, double>>* values) {
  values->emplace_back(key + ".frames", s.frames);
  values->emplace_back(key + ".boundary_found_pct", s.foundPct());
  values->emplace_back(key + ".ms_per_frame", s.frames ? s.ms / s.frames : 0.0);
  for (int c = 0; c < kClassCount; ++c) {
    values->emplace_back(key + "." + kClasses[c] + "_objects", s.classes[c].objects);
    values->emplace_back(key + "." + kClasses[c] + "_on_field_pct", s.classes[c].pct());
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string json;
  double margin_px = 8;
  std::string root;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--json" && i + 1 < argc) {
      json = argv[++i];
    } else if (arg == "--margin-px" && i + 1 < argc) {
      margin_px = std::stod(argv[++i]);
    } else {
      root = arg;
    }
  }
  std::vector<std::string> dates;
  if (!root.empty() && std::filesystem::is_directory(root)) {
    for (const auto& entry : std::filesystem::directory_iterator(root)) {
      if (entry.is_directory()) dates.push_back(entry.path().string());
    }
  }
  std::sort(dates.begin(), dates.end());
  if (dates.empty()) {
    std::fprintf(stderr, "usage: rle_vision_eval_field [--margin-px N] [--json OUT] DIR (its folders: the dates)\n");
    return 2;
  }
  bench::pinToOneCpu();
  std::printf("rle_vision eval (field boundary): each frame alone (field colour seeded on it); an object is on the "
              "field side when its box's bottom centre is at most %.0f px above the boundary\n",
              margin_px);
  std::printf("%-22s %6s %7s %7s   %-14s   %-14s   %-14s\n", "date", "frames", "found%", "ms", "balls on field",
              "robots on field", "humans on field");
  std::vector<std::pair<std::string, double>> values;
  DateScore all;
  double worst_robots = 100;
  for (const std::string& dir : dates) {
    DateScore s;
    for (const std::string& path : imagesUnderFolder(dir)) scoreFrame(path, margin_px, &s);
    const std::string name = std::filesystem::path(dir).filename().string();
    printRow(name, s);
    addValues("dates." + name, s, &values);
    all.frames += s.frames, all.found += s.found, all.ms += s.ms;
    for (int c = 0; c < kClassCount; ++c) {
      all.classes[c].objects += s.classes[c].objects, all.classes[c].on_field += s.classes[c].on_field;
    }
    if (s.classes[1].objects) worst_robots = std::min(worst_robots, s.classes[1].pct());
  }
  printRow("all", all);
  addValues("all", all, &values);
  values.emplace_back("worst_date_obstacle_on_field_pct", worst_robots);
  if (!json.empty()) bench::writeJson(json, values);
  return 0;
}
