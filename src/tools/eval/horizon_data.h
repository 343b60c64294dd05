// The frames make eval scores horizons on, grouped the way they were recorded, and the
// perturbations of the robustness suite (labels transformed with the image).
//
// Groups: a labelled UAV frame's flight is its clip's prefix (file names "a2-converted.mp4-...":
// "a2"); the data set cuts some flights twice, under the letters d and e with the same number
// (d3 and e3 share frames), which are one group "d3+e3" (mergeCutFlights). A frame without a horizon (a folder of
// indoor robot frames) belongs to its first sub-folder under the folder given (a date, a hall).
// Anything chosen from data is chosen without the group it is scored on.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/horizon_metrics.h"
#include "rle_vision/landmark/line_geometry.h"

namespace rle_vision {
namespace eval {

struct HorizonFrame {
  std::string path;     // the image
  std::string dataset;  // the folder's name: uav_horizon, robocup_msl, ...
  std::string group;    // its flight, date or scene
  HorizonLabel label;   // has_horizon false for frames without one
};

// "a2-converted.mp4-00.04.37.277-00.04.54.650_0.jpg" -> "a2".
inline std::string flightOf(const std::string& file) { return file.substr(0, std::min(file.find('-'), file.find('_'))); }

// The flights cut twice (dN and eN both present) become one group "dN+eN".
inline void mergeCutFlights(std::vector<HorizonFrame>* frames) {
  std::vector<std::string> groups;
  for (const HorizonFrame& f : *frames) groups.push_back(f.group);
  auto present = [&](const std::string& g) { return std::find(groups.begin(), groups.end(), g) != groups.end(); };
  for (HorizonFrame& f : *frames) {
    const std::string& g = f.group;
    if (g.size() < 2 || (g[0] != 'd' && g[0] != 'e') || !std::isdigit(static_cast<unsigned char>(g[1]))) continue;
    const std::string number = g.substr(1);
    if (present("d" + number) && present("e" + number)) f.group = "d" + number + "+e" + number;
  }
}

inline std::string folderName(const std::string& dir) {
  return std::filesystem::path(dir).lexically_normal().filename().string().empty()
             ? std::filesystem::path(dir).lexically_normal().parent_path().filename().string()
             : std::filesystem::path(dir).lexically_normal().filename().string();
}

// DIR/label.csv ("filename,slope,offset", the horizon y = slope x + offset H, or with a
// has_horizon column), images in DIR/images/ or DIR/.
inline std::vector<HorizonFrame> labelledFrames(const std::string& dir) {
  std::ifstream in(dir + "/label.csv");
  if (!in) throw std::runtime_error(dir + "/label.csv: cannot open the labels");
  std::vector<HorizonFrame> frames;
  std::string line;
  std::getline(in, line);
  const bool with_flag = line.find("has_horizon") != std::string::npos;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string f; std::getline(row, f, ',');) fields.push_back(f);
    HorizonLabel label;
    label.file = fields.at(0);
    size_t k = 1;
    if (with_flag) label.has_horizon = fields.at(k) == "true" || fields.at(k) == "True" || fields.at(k) == "1", ++k;
    if (label.has_horizon) label.slope = std::stod(fields.at(k)), label.offset = std::stod(fields.at(k + 1));
    HorizonFrame frame;
    frame.path = std::filesystem::exists(dir + "/images/" + label.file) ? dir + "/images/" + label.file : dir + "/" + label.file;
    frame.dataset = folderName(dir);
    frame.group = flightOf(label.file);
    frame.label = label;
    frames.push_back(frame);
  }
  return frames;
}

// Every image under DIR (sorted), none with a horizon; grouped by their first sub-folder.
inline std::vector<HorizonFrame> framesWithoutHorizon(const std::string& dir) {
  std::vector<HorizonFrame> frames;
  if (!std::filesystem::is_directory(dir)) return frames;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (!entry.is_regular_file() || (ext != ".jpg" && ext != ".jpeg" && ext != ".png")) continue;
    HorizonFrame frame;
    frame.path = entry.path().string();
    frame.label.file = entry.path().filename().string();
    frame.label.has_horizon = false;
    frame.dataset = folderName(dir);
    const std::filesystem::path relative = std::filesystem::relative(entry.path(), dir);
    frame.group = frame.dataset + "/" + (relative.has_parent_path() ? relative.begin()->string() : "");
    frames.push_back(frame);
  }
  std::sort(frames.begin(), frames.end(), [](const HorizonFrame& a, const HorizonFrame& b) { return a.path < b.path; });
  return frames;
}

// A perturbation of the robustness suite: the image changed and its horizon moved with it.
struct Perturbation {
  std::string name;
  int kind;       // what is done (see perturb)
  double amount;  // its strength
};

inline std::vector<Perturbation> robustnessSuite() {
  return {{"gamma 0.5", 0, 0.5},          {"gamma 2", 0, 2.0},           {"contrast halved", 1, 0.5},
          {"haze 40%", 2, 0.4},           {"blur sigma 2 px", 3, 2.0},    {"noise sigma 10", 4, 10.0},
          {"JPEG quality 30", 5, 30},     {"rotated +30 deg", 6, 30.0},   {"rotated -30 deg", 6, -30.0},
          {"half size", 7, 0.5}};
}

// The image `bgr` perturbed, and its horizon `truth` (if any) with it. A rotation keeps the
// largest centred square with no border (nothing the camera did not see).
inline cv::Mat perturb(const cv::Mat& bgr, const Perturbation& p, uint64_t seed, ImageLine* truth) {
  cv::Mat out;
  switch (p.kind) {
    case 0: {
      cv::Mat lut(1, 256, CV_8U);
      for (int v = 0; v < 256; ++v) lut.at<uint8_t>(v) = cv::saturate_cast<uint8_t>(255 * std::pow(v / 255.0, p.amount));
      cv::LUT(bgr, lut, out);
      return out;
    }
    case 1: bgr.convertTo(out, -1, p.amount, 128 * (1 - p.amount)); return out;
    case 2: cv::addWeighted(bgr, 1 - p.amount, cv::Mat(bgr.size(), bgr.type(), cv::Scalar::all(200)), p.amount, 0, out); return out;
    case 3: cv::GaussianBlur(bgr, out, cv::Size(), p.amount); return out;
    case 4: {
      cv::Mat noise(bgr.size(), CV_16SC3);
      cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0, p.amount);
      cv::Mat wide;
      bgr.convertTo(wide, CV_16SC3);
      cv::Mat(wide + noise).convertTo(out, CV_8UC3);
      return out;
    }
    case 5: {
      std::vector<uint8_t> jpeg;
      cv::imencode(".jpg", bgr, jpeg, {cv::IMWRITE_JPEG_QUALITY, static_cast<int>(p.amount)});
      return cv::imdecode(jpeg, cv::IMREAD_COLOR);
    }
    case 6: {
      const cv::Point2f centre(0.5f * (bgr.cols - 1), 0.5f * (bgr.rows - 1));
      const cv::Mat rotation = cv::getRotationMatrix2D(centre, p.amount, 1.0);
      cv::Mat rotated;
      cv::warpAffine(bgr, rotated, rotation, bgr.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
      const double a = std::fabs(p.amount) * M_PI / 180;
      const int side = static_cast<int>(std::min(bgr.cols, bgr.rows) / (std::cos(a) + std::sin(a)));
      const cv::Rect crop((bgr.cols - side) / 2, (bgr.rows - side) / 2, side, side);
      if (truth) {
        double x1, y1, x2, y2;
        clipLineToImage(*truth, bgr.cols, bgr.rows, &x1, &y1, &x2, &y2);
        auto map = [&](double x, double y, double* u, double* v) {
          *u = rotation.at<double>(0, 0) * x + rotation.at<double>(0, 1) * y + rotation.at<double>(0, 2) - crop.x;
          *v = rotation.at<double>(1, 0) * x + rotation.at<double>(1, 1) * y + rotation.at<double>(1, 2) - crop.y;
        };
        double u1, v1, u2, v2;
        map(x1, y1, &u1, &v1);
        map(x2, y2, &u2, &v2);
        *truth = lineThroughPoints(u1, v1, u2, v2);
      }
      return rotated(crop).clone();
    }
    default: {
      cv::resize(bgr, out, cv::Size(), p.amount, p.amount, cv::INTER_AREA);
      if (truth) {
        double x1, y1, x2, y2;
        clipLineToImage(*truth, bgr.cols, bgr.rows, &x1, &y1, &x2, &y2);
        // Pixel centres: x' = (x + 0.5) s - 0.5.
        auto scale = [&](double x) { return (x + 0.5) * p.amount - 0.5; };
        *truth = lineThroughPoints(scale(x1), scale(y1), scale(x2), scale(y2));
      }
      return out;
    }
  }
}

}  // namespace eval
}  // namespace rle_vision
