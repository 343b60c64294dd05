// rle_vision_detect: the core pipeline (blobs, lines, horizon) on image files, no roscore.
// Prints one JSON object per image on stdout; unreadable files give an error entry and a
// non-zero exit status at the end.
//
//   rle_vision_detect [--colors FILE] [--params FILE] [--annotate DIR] IMAGE...
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "rle_vision/config_files.h"
#include "rle_vision/landmark_detector.h"
#include "rle_vision/overlay.h"
#include "rle_vision/segmenter.h"

namespace {

using namespace rle_vision;

const char* kUsage =
    "usage: rle_vision_detect [--colors FILE] [--params FILE] [--annotate DIR] IMAGE...\n"
    "  --colors FILE    colour classes: colors.yaml or CMVision colors.txt (default: the package's config/colors.yaml)\n"
    "  --params FILE    landmark parameters (default: the package's config/landmark.yaml values)\n"
    "  --annotate DIR   also write DIR/<image name>.png with blobs, lines and the horizon drawn\n"
    "Prints one JSON object per image: blobs, lines and horizon (theta in radians, DESIGN.md conventions).\n";

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", v);
  return buffer;
}

std::string baseName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

}  // namespace

int main(int argc, char** argv) {
  std::string colors_file = std::string(RLE_VISION_SOURCE_DIR) + "/config/colors.yaml";
  std::string params_file, annotate_dir;
  std::vector<std::string> images;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* name) -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "rle_vision_detect: " << name << " needs a value\n" << kUsage;
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--colors") {
      colors_file = value("--colors");
    } else if (arg == "--params") {
      params_file = value("--params");
    } else if (arg == "--annotate") {
      annotate_dir = value("--annotate");
    } else if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "rle_vision_detect: unknown option " << arg << "\n" << kUsage;
      return 2;
    } else {
      images.push_back(arg);
    }
  }
  if (images.empty()) {
    std::cerr << kUsage;
    return 2;
  }

  std::unique_ptr<ColorTable> table;
  LandmarkOptions options;
  try {
    table = std::make_unique<ColorTable>(loadColorClasses(colors_file));
    if (!params_file.empty()) options = loadLandmarkParams(params_file);
  } catch (const std::exception& e) {
    std::cerr << "rle_vision_detect: " << e.what() << "\n";
    return 2;
  }

  Segmenter segmenter;
  BlobTracker tracker;
  LandmarkDetector detector;
  int failures = 0;
  for (const std::string& path : images) {
    const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty()) {
      std::cout << "{\"file\":" << jsonString(path) << ",\"error\":\"cannot read the image (missing, unreadable or not an image)\"}" << std::endl;
      ++failures;
      continue;
    }
    std::vector<Region> regions;
    std::vector<TrackedBlob> blobs;
    LandmarkResult result;
    try {
      segmenter.segment(image, PixelFormat::BGR8, *table, &regions);
      tracker.reset();  // every image stands alone
      tracker.update(regions, 0.0, &blobs);
      detector.detectInImage(image, options, &result);
    } catch (const std::exception& e) {
      std::cout << "{\"file\":" << jsonString(path) << ",\"error\":" << jsonString(e.what()) << "}" << std::endl;
      ++failures;
      continue;
    }
    std::ostringstream json;
    json << "{\"file\":" << jsonString(path) << ",\"width\":" << image.cols << ",\"height\":" << image.rows << ",\"blobs\":[";
    for (size_t i = 0; i < blobs.size(); ++i) {
      const Region& r = blobs[i].region;
      json << (i ? "," : "") << "{\"id\":" << blobs[i].id << ",\"color\":" << jsonString(table->classes()[r.label - 1].name)
           << ",\"area\":" << r.area << ",\"cx\":" << number(r.cx) << ",\"cy\":" << number(r.cy) << ",\"left\":" << r.left
           << ",\"top\":" << r.top << ",\"right\":" << r.right << ",\"bottom\":" << r.bottom << ",\"bottom_at_cx\":" << r.bottom_at_cx
           << ",\"angle\":" << number(r.angle) << "}";
    }
    json << "],\"lines\":[";
    for (size_t i = 0; i < result.lines.size(); ++i) {
      const DetectedLine& l = result.lines[i];
      json << (i ? "," : "") << "{\"theta\":" << number(l.line.theta) << ",\"intercept\":" << number(l.line.intercept)
           << ",\"x1\":" << number(l.x1) << ",\"y1\":" << number(l.y1) << ",\"x2\":" << number(l.x2) << ",\"y2\":" << number(l.y2)
           << ",\"votes\":" << l.votes << ",\"support\":" << l.support << "}";
    }
    const HorizonEstimate& h = result.horizon;
    json << "],\"horizon\":{\"found\":" << (h.found ? "true" : "false");
    if (h.found) {
      double roll = 0, pitch = 0;
      horizonAttitude(h.line, nullptr, &roll, &pitch);
      json << ",\"theta\":" << number(h.line.theta) << ",\"intercept\":" << number(h.line.intercept) << ",\"x1\":" << number(h.x1)
           << ",\"y1\":" << number(h.y1) << ",\"x2\":" << number(h.x2) << ",\"y2\":" << number(h.y2)
           << ",\"confidence\":" << number(h.confidence) << ",\"roll\":" << number(roll);
    }
    json << "}}";
    std::cout << json.str() << std::endl;

    if (!annotate_dir.empty()) {
      cv::Mat canvas = image.clone();
      drawBlobs(&canvas, blobs, *table);
      double roll = 0, pitch = 0;
      if (h.found) horizonAttitude(h.line, nullptr, &roll, &pitch);
      drawLandmarks(&canvas, result.lines, h, roll, pitch);
      const std::string out = annotate_dir + "/" + baseName(path) + ".png";
      if (!cv::imwrite(out, canvas)) {
        std::cerr << "rle_vision_detect: cannot write " << out << "\n";
        ++failures;
      }
    }
  }
  return failures == 0 ? 0 : 1;
}
