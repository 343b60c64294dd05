// rle_vision_detect: the core pipeline (blobs, lines, horizon) on image files, no roscore.
// Prints one JSON object per image on stdout; unreadable files give an error entry and a
// non-zero exit status at the end.
//
//   rle_vision_detect [--colors FILE] [--verifier FILE [--min-score S]] [--params FILE] [--horizon-model FILE]
//                     [--annotate DIR] [--sequence [--fps HZ]] IMAGE...
//   rle_vision_detect --print-params
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "detect_json.h"
#include "rle_vision/pipeline/camera_stream.h"
#include "rle_vision/io/color_config.h"
#include "rle_vision/io/data_files.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/io/horizon_model_file.h"
#include "rle_vision/io/landmark_params_file.h"
#include "rle_vision/pipeline/overlay.h"
#include "rle_vision/tracking/color_tracker.h"
#include "rle_vision/verify/candidate_screen.h"

namespace {

using namespace rle_vision;

const char* kUsage =
    "usage: rle_vision_detect [--colors FILE] [--verifier FILE [--min-score S]] [--params FILE] [--horizon-model FILE]\n"
    "                         [--annotate DIR] [--sequence [--fps HZ]] IMAGE...\n"
    "       rle_vision_detect --print-params\n"
    "  --colors FILE    colour classes: colors.yaml or CMVision colors.txt (default: the package's config/colors.yaml)\n"
    "  --verifier FILE  a verifier (rle_vision_train) screens the blobs of the class it was trained for: blobs\n"
    "                   scoring under --min-score (default 0.5) are left out, the others carry their score; a\n"
    "                   class of that name not in the colours gets the verifier's own candidate range, first\n"
    "  --params FILE    landmark parameters (default: their defaults; see --print-params)\n"
    "  --horizon-model FILE  the horizon model (default: the package's config/horizon_model.yaml; none: no model)\n"
    "  --annotate DIR   also write DIR/<image name>.png with blobs, lines and the horizon drawn (DIR is made)\n"
    "  --sequence       the images, in the order given, are one camera stream at --fps (default 30):\n"
    "                   blobs are tracked across them and colour ranges learned on one frame are used on\n"
    "                   the next (parameters learning, learning_*); each line also gives the ranges in use\n"
    "  --print-params   print every landmark parameter with its default, limits and meaning (YAML), and exit\n"
    "Prints one JSON object per image: blobs, lines and horizon (theta in radians, x right, y down,\n"
    "intercept on y below 45 deg and on x from there; see docs/ARCHITECTURE.md, Conventions).\n";

struct Arguments {
  std::string colors_file = packageDataFile("config/colors.yaml");
  std::string params_file, annotate_dir, horizon_model, verifier_file;
  double min_score = 0.5;
  bool min_score_given = false;
  bool print_params = false, sequence = false, fps_given = false;
  double fps = 30;
  std::vector<std::string> images;
};

// The arguments, or an exit status (usage errors: 2; --help: 0) in *exit_status.
bool parseArguments(int argc, char** argv, Arguments* args, int* exit_status) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--colors" || arg == "--params" || arg == "--annotate" || arg == "--horizon-model" || arg == "--verifier") {
      if (!has_value) {
        std::cerr << "rle_vision_detect: " << arg << " needs a value\n" << kUsage;
        *exit_status = 2;
        return false;
      }
      (arg == "--colors" ? args->colors_file
       : arg == "--params" ? args->params_file
       : arg == "--annotate" ? args->annotate_dir
       : arg == "--verifier" ? args->verifier_file
                             : args->horizon_model) = argv[++i];
    } else if (arg == "--fps") {
      char* end = nullptr;
      args->fps = has_value ? std::strtod(argv[++i], &end) : 0;
      args->fps_given = true;
      if (!has_value || *end != '\0' || !(args->fps > 0 && args->fps < 1e6)) {
        std::cerr << "rle_vision_detect: --fps needs a frame rate > 0 (Hz)\n" << kUsage;
        *exit_status = 2;
        return false;
      }
    } else if (arg == "--min-score") {
      char* end = nullptr;
      args->min_score = has_value ? std::strtod(argv[++i], &end) : -1;
      args->min_score_given = true;
      if (!has_value || *end != '\0' || !(args->min_score >= 0 && args->min_score <= 1)) {
        std::cerr << "rle_vision_detect: --min-score needs a score from 0 to 1\n" << kUsage;
        *exit_status = 2;
        return false;
      }
    } else if (arg == "--print-params") {
      args->print_params = true;
    } else if (arg == "--sequence") {
      args->sequence = true;
    } else if (arg == "-h" || arg == "--help") {
      std::cout << kUsage << "Default colours file: "
                << (args->colors_file.empty() ? "(not found: give --colors)" : args->colors_file) << "\n";
      *exit_status = 0;
      return false;
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "rle_vision_detect: unknown option " << arg << "\n" << kUsage;
      *exit_status = 2;
      return false;
    } else {
      args->images.push_back(arg);
    }
  }
  if (args->min_score_given && args->verifier_file.empty()) {
    std::cerr << "rle_vision_detect: --min-score needs --verifier\n" << kUsage;
    *exit_status = 2;
    return false;
  }
  if (args->fps_given && !args->sequence) {
    std::cerr << "rle_vision_detect: --fps needs --sequence (single images have no time)\n" << kUsage;
    *exit_status = 2;
    return false;
  }
  if (args->images.empty() && !args->print_params) {
    std::cerr << kUsage;
    *exit_status = 2;
    return false;
  }
  return true;
}

std::string baseName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

// Writes `out`: the image with blobs, lines and the horizon drawn.
bool annotate(const cv::Mat& image, const std::vector<TrackedBlob>& blobs, const ColorTable& table,
              const LandmarkResult& result, const FieldResult& field, const std::string& out) {
  cv::Mat canvas = image.clone();
  drawFieldBoundary(&canvas, field.boundary);
  drawBlobs(&canvas, blobs, table);
  double roll = 0, pitch = 0;
  if (result.horizon.found) horizonAttitude(result.horizon.line, nullptr, &roll, &pitch);
  drawLandmarks(&canvas, result.lines, result.horizon, roll, pitch);
  if (cv::imwrite(out, canvas)) return true;
  std::cerr << "rle_vision_detect: cannot write " << out << "\n";
  return false;
}

// Every image stands alone: the pipeline's steps on one image file.
class ImageDetector {
 public:
  ImageDetector(const std::vector<ColorClass>& classes, const LandmarkOptions& options, const FieldOptions& field)
      : classes_(classes), screen_(loadClassVerifiers(classes)), table_(withFloorGuard(classes, screen_.verifiers())),
        options_(options), field_options_(field) {
    for (const ColorClass& c : classes) {
      if (c.name == kFieldClassName) configured_field_ = std::make_unique<ColorClass>(c);
    }
  }

  // Prints the image's JSON line (or its error); false on an error.
  bool run(const std::string& path, const std::string& annotate_dir) {
    const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty()) {
      std::cout << errorJson(path, "cannot read the image (missing, unreadable or not an image)") << std::endl;
      return false;
    }
    std::vector<TrackedBlob> blobs;
    LandmarkResult result;
    FieldResult field;
    std::unique_ptr<ColorTable> floor_first;
    try {
      FieldDetector field_detector(field_options_);  // the field colour seeded on this image
      if (configured_field_) field_detector.setConfiguredColour(*configured_field_);
      field_detector.detect(image, &field);
      // A verifier judges candidates made as in training: the image's floor colour first.
      if (!screen_.empty() && field.colour.found) {
        floor_first = std::make_unique<ColorTable>(
            withFloorGuard(withFloorFirst(classes_, field.colour.range), screen_.verifiers()));
      }
      const ColorTable& table = floor_first ? *floor_first : table_;
      ColorTracker tracker;  // a new one per image: nothing carries over
      tracker.process(image, PixelFormat::BGR8, table, 0.0, &blobs);
      screen_.apply(image, table, &blobs);
      detector_.detectInImage(image, options_, &result);
    } catch (const std::exception& e) {
      std::cout << errorJson(path, e.what()) << std::endl;
      return false;
    }
    const ColorTable& table = floor_first ? *floor_first : table_;
    std::cout << detectionJson(path, image.cols, image.rows, blobs, table, result, field) << std::endl;
    return annotate_dir.empty() ||
           annotate(image, blobs, table, result, field, annotate_dir + "/" + baseName(path) + ".png");
  }

 private:
  std::vector<ColorClass> classes_;
  CandidateScreen screen_;  // classes with a verifier
  ColorTable table_;        // the classes, with the floor's guard before a verified class (after screen_: it needs the verifiers)
  LandmarkOptions options_;
  FieldOptions field_options_;
  std::unique_ptr<ColorClass> configured_field_;  // the colours file's field class, if any
  LandmarkDetector detector_;
};

// The images are one camera stream (rle_vision/camera_stream.h); time is the frame index over
// the frame rate.
class SequenceDetector {
 public:
  SequenceDetector(const std::vector<ColorClass>& classes, const CameraStreamOptions& options, double fps)
      : stream_(classes, options), frame_period_s_(1.0 / fps) {}

  bool run(const std::string& path, const std::string& annotate_dir) {
    const double stamp_s = frame_period_s_ * frames_++;
    const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty()) {
      std::cout << errorJson(path, "cannot read the image (missing, unreadable or not an image)") << std::endl;
      return false;
    }
    CameraStream::Frame frame;
    try {
      stream_.process(image, stamp_s, &frame);
    } catch (const std::exception& e) {
      std::cout << errorJson(path, e.what()) << std::endl;
      return false;
    }
    if (!frame.ignored_ranges.empty()) {
      std::cerr << "rle_vision_detect: ignoring learned ranges after " << path << ": " << frame.ignored_ranges << "\n";
    }
    std::cout << detectionJson(path, image.cols, image.rows, frame.blobs, *frame.table, frame.landmarks, frame.field,
                               true)
              << std::endl;
    return annotate_dir.empty() || annotate(image, frame.blobs, *frame.table, frame.landmarks, frame.field,
                                            annotate_dir + "/" + baseName(path) + ".png");
  }

 private:
  CameraStream stream_;
  double frame_period_s_;
  long frames_ = 0;
};

int runSequence(const Arguments& args, const std::vector<ColorClass>& classes, const LandmarkOptions& options) {
  CameraStreamOptions stream;
  stream.landmark = options;
  if (!args.params_file.empty()) {
    stream.learning = loadLearningParams(args.params_file);
    stream.loop = loadLearningLoopParams(args.params_file);
    stream.field = loadFieldParams(args.params_file);
  }
  SequenceDetector sequence(classes, stream, args.fps);
  int failures = 0;
  for (const std::string& path : args.images) failures += sequence.run(path, args.annotate_dir) ? 0 : 1;
  return failures == 0 ? 0 : 1;
}

// The colour classes, with --verifier attached to the class it was trained for. When the colours
// have no class of that name, the verifier's candidate range is added first: it wins the pixels
// it shares with other classes, as it did in training (a table of that class alone).
std::vector<ColorClass> colorClasses(const Arguments& args) {
  std::vector<ColorClass> classes = loadColorClasses(args.colors_file);
  if (args.verifier_file.empty()) return classes;
  const ColorClass range = BlobVerifier::load(args.verifier_file).candidateRange();
  auto it = std::find_if(classes.begin(), classes.end(), [&](const ColorClass& c) { return c.name == range.name; });
  if (it == classes.end()) it = classes.insert(classes.begin(), range);
  it->verifier_file = it->verifier_path = args.verifier_file;
  it->min_score = args.min_score;
  const std::string problem = validateColorClasses(classes);
  if (!problem.empty()) throw ConfigError(args.verifier_file + ": " + problem);
  return classes;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  int exit_status = 0;
  if (!parseArguments(argc, argv, &args, &exit_status)) return exit_status;
  if (args.print_params) {
    std::cout << defaultLandmarkParamsYaml();
    return 0;
  }
  std::unique_ptr<ImageDetector> detector;
  std::error_code folder_error;
  if (!args.annotate_dir.empty() && !std::filesystem::is_directory(args.annotate_dir) &&
      !std::filesystem::create_directories(args.annotate_dir, folder_error)) {
    std::cerr << "rle_vision_detect: cannot create the --annotate folder " << args.annotate_dir << ": "
              << folder_error.message() << "\n";
    return 2;
  }
  try {
    if (args.colors_file.empty()) {
      throw ConfigError("config/colors.yaml not found (installed share/rle_vision, the source tree or "
                        "$RLE_VISION_DATA_DIR): give --colors FILE");
    }
    LandmarkOptions options = args.params_file.empty() ? LandmarkOptions() : loadLandmarkParams(args.params_file);
    options.horizon.model = horizonModelFromSetting(args.horizon_model);
    if (args.sequence) return runSequence(args, colorClasses(args), options);
    const FieldOptions field = args.params_file.empty() ? FieldOptions() : loadFieldParams(args.params_file);
    detector = std::make_unique<ImageDetector>(colorClasses(args), options, field);
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_detect: " << e.what() << "\n";
    return 2;
  }
  int failures = 0;
  for (const std::string& path : args.images) failures += detector->run(path, args.annotate_dir) ? 0 : 1;
  return failures == 0 ? 0 : 1;
}
