// For the calibration window's test (test/gui/test_calibrate_gui.sh): a simulator frame with
// its exact object masks, and the check of a calibrated class against it.
//
//   calibration_scene write SCENE_FILE DIR   frame.png, labels.png (the simulator's label
//                                            image) and box.txt: "label left top right bottom"
//                                            of the largest object no other object touches,
//                                            then a line of the labels of every object painted
//                                            its colour (itself included)
//   calibration_scene check DIR COLORS NAME  the class NAME of COLORS (colors.yaml or
//                                            colors.txt) on frame.png: the share of the object's
//                                            pixels it takes, and its pixels elsewhere; exit 0
//                                            when it takes >= 95% of the object and no region of
//                                            min_area_px elsewhere (the tracker would report
//                                            none) but on objects of the same paint
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rle_vision/color/classifier.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/sim/scene_file.h"
#include "rle_vision/sim/scene_simulator.h"

namespace {

using namespace rle_vision;

int write(const std::string& scene_file, const std::string& dir) {
  const SceneSimulator simulator(loadSceneConfig(scene_file));
  const SimFrame frame = simulator.render(0, 0.0);
  const BoxTruth* best = nullptr;
  for (const BoxTruth& b : frame.boxes) {
    if (b.area > 0 && !b.touches_other_box && b.pieces == 1 && (best == nullptr || b.area > best->area)) best = &b;
  }
  if (best == nullptr) {
    std::fprintf(stderr, "calibration_scene: no object stands alone in %s\n", scene_file.c_str());
    return 1;
  }
  if (!cv::imwrite(dir + "/frame.png", frame.image) || !cv::imwrite(dir + "/labels.png", frame.labels)) {
    std::fprintf(stderr, "calibration_scene: cannot write into %s\n", dir.c_str());
    return 1;
  }
  std::ofstream(dir + "/box.txt") << static_cast<int>(best->label) << " " << best->left << " " << best->top << " "
                                  << best->right << " " << best->bottom << "\n";
  std::ofstream same_paint(dir + "/box.txt", std::ios::app);
  for (const BoxTruth& b : frame.boxes) {
    if (b.color_class == best->color_class) same_paint << static_cast<int>(b.label) << " ";
  }
  same_paint << "\n";
  std::printf("%s (%s): %u px in [%d %d]..[%d %d]\n", best->name.c_str(), best->color_class.c_str(), best->area,
              best->left, best->top, best->right, best->bottom);
  return 0;
}

int check(const std::string& dir, const std::string& colors, const std::string& name) {
  const cv::Mat bgr = cv::imread(dir + "/frame.png", cv::IMREAD_COLOR);
  const cv::Mat labels = cv::imread(dir + "/labels.png", cv::IMREAD_GRAYSCALE);
  int label = -1;
  std::ifstream box_file(dir + "/box.txt");
  box_file >> label;
  std::string box_rest, same_paint_line;
  std::getline(box_file, box_rest);
  std::getline(box_file, same_paint_line);
  const ColorClass* c = nullptr;
  const std::vector<ColorClass> classes = loadColorClasses(colors);
  for (const ColorClass& k : classes) {
    if (k.name == name) c = &k;
  }
  if (bgr.empty() || labels.empty() || label < 0 || c == nullptr) {
    std::fprintf(stderr, "calibration_scene: %s has no class '%s', or %s lacks the scene\n", colors.c_str(),
                 name.c_str(), dir.c_str());
    return 1;
  }
  const cv::Mat in_class = colorClassMask(*c, bgr);
  const cv::Mat object = labels == label;
  // Another object of the same paint is rightly in the class: "elsewhere" is off all of them.
  cv::Mat same_paint = object.clone();
  std::istringstream same_paint_labels(same_paint_line);
  for (int other; same_paint_labels >> other;) same_paint |= labels == other;
  cv::Mat taken, elsewhere, regions, stats, centroids;
  cv::bitwise_and(in_class, object, taken);
  cv::bitwise_and(in_class, ~same_paint, elsewhere);
  const int count = cv::connectedComponentsWithStats(elsewhere, regions, stats, centroids, 8);
  int big_regions = 0;
  for (int i = 1; i < count; ++i) big_regions += stats.at<int>(i, cv::CC_STAT_AREA) >= static_cast<int>(c->min_area_px);
  const double recall = static_cast<double>(cv::countNonZero(taken)) / cv::countNonZero(object);
  std::printf("%s: %.1f%% of the object's %d px; elsewhere %d px in %d regions of >= %u px\n", colors.c_str(),
              100 * recall, cv::countNonZero(object), cv::countNonZero(elsewhere), big_regions, c->min_area_px);
  return recall >= 0.95 && big_regions == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 4 && std::string(argv[1]) == "write") return write(argv[2], argv[3]);
    if (argc == 5 && std::string(argv[1]) == "check") return check(argv[2], argv[3], argv[4]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "calibration_scene: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "usage: calibration_scene write SCENE_FILE DIR | check DIR COLORS NAME\n");
  return 2;
}
