// make eval (field boundary): on labelled robot frames, how often the field boundary is found and
// how many labelled objects standing on the field (balls, robots, people's feet: each box's
// bottom centre) it puts on the field side, per recording date (a date is one hall and light:
// the grouping make eval reports its worst of). Each frame stands alone: the field colour is
// seeded on it, nothing is tuned on these frames.
//
//   rle_vision_eval_field [--margin-px N] [--non-field-penalty P] [--json OUT] [--sheet PNG [--sheet-class C]] DIR
//
// --sheet draws every object of class C (default 1, the robots) that it puts off the field side
// into one contact sheet, the boundary in magenta and the box in red, each tile numbered and
// labelled with how far above the boundary the box's bottom is (px): whether those objects
// stand on this field at all (another field, the hall floor beside the carpet, a ball in the air)
// is for a person to see, since the labels do not say. --non-field-penalty sets the field stage's
// field_non_field_penalty (default 1.0; docs/performance.md has a sweep).
//
// DIR's folders are the dates; each holds folders of images with YOLO label files beside them
// (classes 0 ball, 1 obstacle, 2 human, as robocup_ml's obj.names).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "field_options_arg.h"
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

// The off-field objects of one class, a tile each (the frame around the box, the boundary drawn).
struct OffFieldSheet {
  static constexpr int kTile = 200;
  int label_class = 1;
  std::vector<cv::Mat> tiles;
  std::vector<std::string> captions;

  void add(const cv::Mat& image, const FieldBoundaryEstimate& boundary, const cv::Rect& box, double above,
           const std::string& path) {
    cv::Mat drawn = image.clone();
    for (size_t i = 1; i < boundary.polyline.size(); ++i) {
      cv::line(drawn, boundary.polyline[i - 1], boundary.polyline[i], cv::Scalar(255, 0, 255), 2);
    }
    cv::rectangle(drawn, box, cv::Scalar(0, 0, 255), 2);
    const cv::Point centre(box.x + box.width / 2, box.y + box.height / 2);
    const cv::Rect crop = cv::Rect(centre.x - kTile / 2, centre.y - kTile / 2, kTile, kTile) & cv::Rect(cv::Point(), image.size());
    cv::Mat tile(kTile, kTile, CV_8UC3, cv::Scalar::all(0));
    drawn(crop).copyTo(tile(cv::Rect(crop.x - (centre.x - kTile / 2), crop.y - (centre.y - kTile / 2), crop.width, crop.height)));
    const std::string caption = std::to_string(tiles.size()) + ": " + std::to_string(static_cast<int>(std::lround(above))) + " px";
    cv::putText(tile, caption, cv::Point(4, 16), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 255, 255), 1);
    tiles.push_back(tile);
    captions.push_back(caption + " above, " + path);
  }

  // The tiles, 8 to a row; false when there are none or the file cannot be written.
  bool write(const std::string& png) const {
    constexpr int kColumns = 8;
    if (tiles.empty()) return false;
    const int rows = static_cast<int>((tiles.size() + kColumns - 1) / kColumns);
    cv::Mat sheet(rows * kTile, kColumns * kTile, CV_8UC3, cv::Scalar::all(40));
    for (size_t i = 0; i < tiles.size(); ++i) {
      tiles[i].copyTo(sheet(cv::Rect(static_cast<int>(i % kColumns) * kTile, static_cast<int>(i / kColumns) * kTile, kTile, kTile)));
    }
    return cv::imwrite(png, sheet);
  }
};

// One frame: the boundary, and each labelled object's bottom centre against it.
void scoreFrame(const std::string& path, const FieldOptions& options, double margin_px, DateScore* s, OffFieldSheet* sheet) {
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) return;
  FieldDetector detector(options);  // seeded on this frame alone
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
      if (sheet && c == sheet->label_class && above > margin_px) sheet->add(image, field.boundary, box, above, path);
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

int usage(const std::string& problem) {
  if (!problem.empty()) std::fprintf(stderr, "rle_vision_eval_field: %s\n", problem.c_str());
  std::fprintf(stderr, "usage: rle_vision_eval_field [--margin-px N] [--non-field-penalty P] [--json OUT] "
                       "[--sheet PNG [--sheet-class C]] DIR (its folders: the dates)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string json, sheet_png;
  OffFieldSheet sheet;
  double margin_px = 8;
  FieldOptions options;
  std::string root, problem;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--json" && i + 1 < argc) {
      json = argv[++i];
    } else if (arg == "--margin-px" && i + 1 < argc) {
      if (!bench::isFiniteNumber(argv[++i], &margin_px) || margin_px < 0) return usage("--margin-px needs a number >= 0");
    } else if (arg == "--non-field-penalty" && i + 1 < argc) {
      if (!bench::parseNonFieldPenalty(argv[++i], &options, &problem)) return usage(problem);
    } else if (arg == "--sheet" && i + 1 < argc) {
      sheet_png = argv[++i];
    } else if (arg == "--sheet-class" && i + 1 < argc) {
      const std::string label_class = argv[++i];
      if (!bench::isWholeNumber(label_class, 6)) return usage("--sheet-class needs a whole number >= 0");
      sheet.label_class = std::stoi(label_class);
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
  if (dates.empty()) return usage("");
  bench::pinToOneCpu();
  std::printf("rle_vision eval (field boundary): each frame alone (field colour seeded on it); an object is on the "
              "field side when its box's bottom centre is at most %.0f px above the boundary (non-field penalty %g)\n",
              margin_px, options.boundary.non_field_penalty);
  std::printf("%-22s %6s %7s %7s   %-14s   %-14s   %-14s\n", "date", "frames", "found%", "ms", "balls on field",
              "robots on field", "humans on field");
  std::vector<std::pair<std::string, double>> values;
  DateScore all;
  double worst_robots = 100;
  for (const std::string& dir : dates) {
    DateScore s;
    for (const std::string& path : imagesUnderFolder(dir)) scoreFrame(path, options, margin_px, &s, sheet_png.empty() ? nullptr : &sheet);
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
  if (!sheet_png.empty()) {
    for (const std::string& caption : sheet.captions) std::printf("  off the field side, tile %s\n", caption.c_str());
    std::printf("%s: %zu objects of class %d off the field side%s\n", sheet_png.c_str(), sheet.tiles.size(), sheet.label_class,
                sheet.write(sheet_png) ? "" : " (none drawn: none, or the file cannot be written)");
  }
  return 0;
}
