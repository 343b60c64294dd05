// rle_vision_calibrate: a colour class from example images with boxes around the object (see
// rle_vision/color_calibration.h); prints it as a colors.yaml entry and a CMVision colors.txt.
//
//   rle_vision_calibrate --name ball IMAGE --box x0,y0,x1,y1 [--box ...] [IMAGE --box ...]...
//   rle_vision_calibrate --name ball --label-class 0 FOLDER_OR_IMAGE...   (YOLO labels)
//   rle_vision_calibrate --gui --name ball IMAGE...   (drag the boxes in a window)
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "calibrate_gui/calibration_window.h"
#include "rle_vision/learning/calibration_session.h"
#include "rle_vision/learning/calibration_view.h"
#include "rle_vision/learning/color_calibration.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/io/yolo_labels.h"

namespace {

using namespace rle_vision;

const char* kUsage =
    "usage: rle_vision_calibrate --name NAME [options] IMAGE --box x0,y0,x1,y1 [--box ...] [IMAGE --box ...]...\n"
    "       rle_vision_calibrate --name NAME --label-class N [options] FOLDER_OR_IMAGE...\n"
    "       rle_vision_calibrate --gui --name NAME [options] IMAGE... (boxes optional: drag them in the window)\n"
    "  --gui              a window: drag boxes around the object over the images, watch the class's mask\n"
    "                     (keys on screen: u undo, n/b next/back image, c colour space, s save, q quit);\n"
    "                     needs a display (DISPLAY; 'xvfb-run -a' for a virtual one)\n"
    "  --box x0,y0,x1,y1  a box around the object in the image named before it (pixels; x1,y1 one past\n"
    "                     the last column and row); an image without boxes shows colours the class must avoid\n"
    "  --label-class N    boxes of class N from the YOLO label file beside each image (IMAGE.txt:\n"
    "                     'class cx cy w h', normalised; none: no boxes); a FOLDER means its .jpg/.png images\n"
    "  --space S          YUV (default), RGB or HSV\n"
    "  --min-area PX      the class's min_area_px (default 20)\n"
    "  --no-background-gate  keep the statistics' range (mean +- 3 sigma) instead of tightening it\n"
    "                     against the labelled images' other pixels\n"
    "  --output FILE      also write the class into FILE (colors.yaml; a class of the same name is\n"
    "                     replaced, the others kept; comments are not kept)\n"
    "  --cmvision FILE    the same for a CMVision colors.txt (YUV classes only)\n"
    "Prints the class as colors.yaml text, then (YUV) as colors.txt; a summary goes to stderr.\n"
    "HSV: hue ranges that wrap around 0 (red) are not produced; calibrate red in YUV.\n"
    "Exit status: 0 done, 2 bad input (unreadable image, box outside its image, empty box, no object).\n";

struct Arguments {
  std::string name, output, cmvision;
  int label_class = -1;
  bool gui = false;
  CalibrationOptions options;
  std::vector<std::string> images;
  std::vector<std::vector<cv::Rect>> boxes;  // per image, from --box
};

struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

cv::Rect parseBox(const std::string& text) {
  int x0, y0, x1, y1;
  char c1, c2, c3, rest;
  std::istringstream in(text);
  if (!(in >> x0 >> c1 >> y0 >> c2 >> x1 >> c3 >> y1) || c1 != ',' || c2 != ',' || c3 != ',' || (in >> rest)) {
    throw UsageError("--box needs x0,y0,x1,y1 (four integers), got '" + text + "'");
  }
  const int kLimit = 1 << 20;  // far beyond any image; keeps x1 - x0 from overflowing
  if (std::abs(x0) > kLimit || std::abs(y0) > kLimit || std::abs(x1) > kLimit || std::abs(y1) > kLimit) {
    throw UsageError("--box " + text + ": coordinates out of range");
  }
  return cv::Rect(x0, y0, x1 - x0, y1 - y0);  // x1 <= x0 gives an empty box, refused with its example
}

int parseInt(const std::string& option, const std::string& text, int minimum) {
  size_t used = 0;
  int value = -1;
  try {
    value = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || value < minimum) {
    throw UsageError(option + " needs a whole number >= " + std::to_string(minimum) + ", got '" + text + "'");
  }
  return value;
}

void parseOption(const std::string& arg, const std::string& value, Arguments* args) {
  if (arg == "--name") args->name = value;
  else if (arg == "--output") args->output = value;
  else if (arg == "--cmvision") args->cmvision = value;
  else if (arg == "--label-class") args->label_class = parseInt(arg, value, 0);
  else if (arg == "--min-area") args->options.min_area_px = static_cast<uint32_t>(parseInt(arg, value, 1));
  else if (arg == "--space" && !parseColorSpace(value, &args->options.space)) throw UsageError("unknown --space " + value);
  else if (arg == "--box") {
    if (args->images.empty()) throw UsageError("--box " + value + " comes before any image: name the image first");
    args->boxes.back().push_back(parseBox(value));
  }
}

Arguments parseArguments(int argc, char** argv) {
  Arguments args;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--name" || arg == "--output" || arg == "--cmvision" || arg == "--label-class" ||
        arg == "--min-area" || arg == "--space" || arg == "--box") {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      parseOption(arg, argv[++i], &args);
    } else if (arg == "--no-background-gate") {
      args.options.exclude_background = false;
    } else if (arg == "--gui") {
      args.gui = true;
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else {
      args.images.push_back(arg);
      args.boxes.emplace_back();
    }
  }
  if (!isPortableClassName(args.name)) {
    throw UsageError("--name NAME is required: letters, digits, '_' and '-' (it goes into colors.yaml and colors.txt)");
  }
  if (args.images.empty()) throw UsageError("no images given");
  const bool has_boxes = std::any_of(args.boxes.begin(), args.boxes.end(), [](const auto& b) { return !b.empty(); });
  if (has_boxes && args.label_class >= 0) throw UsageError("give --box or --label-class, not both");
  if (!args.cmvision.empty() && args.options.space != ColorSpace::YUV) {
    throw UsageError("--cmvision needs --space YUV: CMVision's colors.txt holds YUV ranges only");
  }
  return args;
}

bool isDirectory(const std::string& path) {
  struct stat s;
  return stat(path.c_str(), &s) == 0 && S_ISDIR(s.st_mode);
}

CalibrationExample readExample(const std::string& path, std::vector<cv::Rect> boxes, int label_class) {
  if (label_class >= 0) return readYoloExample(path, label_class);
  CalibrationExample e;
  e.name = path;
  e.bgr = cv::imread(path, cv::IMREAD_COLOR);
  if (e.bgr.empty()) throw std::invalid_argument(path + ": cannot read the image (missing, unreadable or not an image)");
  e.boxes = std::move(boxes);
  return e;
}

std::vector<CalibrationExample> readExamples(const Arguments& args, bool need_boxes) {
  std::vector<CalibrationExample> examples;
  for (size_t i = 0; i < args.images.size(); ++i) {
    if (args.label_class >= 0 && isDirectory(args.images[i])) {
      const std::vector<std::string> files = imagesInFolder(args.images[i]);
      if (files.empty()) throw std::invalid_argument(args.images[i] + ": no .jpg or .png images in the folder");
      for (const std::string& f : files) examples.push_back(readExample(f, {}, args.label_class));
    } else {
      examples.push_back(readExample(args.images[i], args.boxes[i], args.label_class));
    }
  }
  size_t boxes = 0;
  for (const CalibrationExample& e : examples) boxes += e.boxes.size();
  if (need_boxes && boxes == 0) throw std::invalid_argument("no boxes: give --box after an image, or --label-class with YOLO labels");
  return examples;
}

void report(const CalibrationResult& r) {
  const ColorStats& s = r.stats;
  std::fprintf(stderr,
               "rle_vision_calibrate: %d boxes used, %d dropped (no object pixels or a colour far from the others)\n"
               "  statistics: mean %.1f %.1f %.1f, sigma %.1f %.1f %.1f, range [%d %d %d]..[%d %d %d]\n"
               "  class: [%d %d %d]..[%d %d %d] holds %.0f%% of each object's pixels; %.0f other pixels per image\n",
               r.boxes_used, r.boxes_dropped, s.mean[0], s.mean[1], s.mean[2], s.sigma[0], s.sigma[1], s.sigma[2],
               s.lo[0], s.lo[1], s.lo[2], s.hi[0], s.hi[1], s.hi[2], r.color_class.min[0], r.color_class.min[1],
               r.color_class.min[2], r.color_class.max[0], r.color_class.max[1], r.color_class.max[2],
               100 * r.object_recall, r.other_pixels_per_image);
}

void printClass(const ColorClass& c) {
  std::cout << colorClassesToYaml({c});
  if (c.space == ColorSpace::YUV) std::cout << "\n" << cmvisionColorsText({c});
}

// What the save key did, for the window's notice line.
std::string save(const CalibrationSession& session, const Arguments& args) {
  if (session.result() && args.output.empty() && args.cmvision.empty()) {
    printClass(session.result()->color_class);
    return "printed to the terminal (--output FILE and --cmvision FILE write files)";
  }
  return saveSessionClass(session, args.output, args.cmvision);
}

// The window over the images; on quit, the last class is printed as the batch mode does.
int runGui(const Arguments& args) {
  const std::string problem = displayProblem();
  if (!problem.empty()) {
    std::cerr << "rle_vision_calibrate: " << problem << "\n";
    return 2;
  }
  CalibrationSession session(args.name, args.options);
  session.addExamples(readExamples(args, false));
  CalibrationWindow window(&session, /*live=*/false);
  int reported = session.revision();
  for (CalibrationCommand command = CalibrationCommand::kNone; command != CalibrationCommand::kQuit;) {
    command = window.step(30);
    if (session.revision() != reported) {  // a box, an undo or a colour space: the class as it is now
      reported = session.revision();
      std::cerr << "rle_vision_calibrate: " << calibrationStatus(session, MaskCounts()).front() << "\n";
    }
    if (command == CalibrationCommand::kSave) {
      const std::string notice = save(session, args);
      std::cerr << "rle_vision_calibrate: " << notice << "\n";
      window.setNotice(notice);
    }
  }
  if (!session.result()) {
    std::cerr << "rle_vision_calibrate: no class (" << (session.lastError().empty() ? "no boxes" : session.lastError())
              << ")\n";
    return 0;
  }
  report(*session.result());
  printClass(session.result()->color_class);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help") {
      std::cout << kUsage;
      return 0;
    }
  }
  try {
    const Arguments args = parseArguments(argc, argv);
    if (args.gui) return runGui(args);
    const CalibrationResult result = calibrateColorClass(readExamples(args, true), args.name, args.options);
    report(result);
    printClass(result.color_class);
    saveColorClassInto(result.color_class, args.output, args.cmvision);
  } catch (const UsageError& e) {
    std::cerr << "rle_vision_calibrate: " << e.what() << "\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_calibrate: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
