#include "rle_vision/io/yolo_labels.h"

#include <dirent.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "rle_vision/io/config_error.h"

namespace rle_vision {

std::string yoloLabelPath(const std::string& image_path) {
  const size_t dot = image_path.find_last_of('.'), slash = image_path.find_last_of('/');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_extension ? image_path.substr(0, dot) : image_path) + ".txt";
}

std::vector<cv::Rect> readYoloBoxes(const std::string& label_path, int label_class, const cv::Size& size) {
  std::vector<cv::Rect> boxes;
  std::ifstream in(label_path);
  if (!in) return boxes;  // YOLO's convention: an image without objects has no label file
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const std::string where = label_path + ":" + std::to_string(line_number) + ": ";
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream fields(line);
    int cls;
    double cx, cy, w, h;
    std::string rest;
    if (!(fields >> cls >> cx >> cy >> w >> h) || (fields >> rest)) {
      throw ConfigError(where + "expected 'class cx cy w h' (a box label, not a polygon)");
    }
    if (cls != label_class) continue;
    if (!(w > 0 && h > 0)) throw ConfigError(where + "the box is empty (w and h must be > 0)");
    const cv::Point p0(static_cast<int>(std::lround((cx - w / 2) * size.width)),
                       static_cast<int>(std::lround((cy - h / 2) * size.height)));
    // At least one pixel, however small the normalised box.
    const cv::Point p1(std::max(p0.x + 1, static_cast<int>(std::lround((cx + w / 2) * size.width))),
                       std::max(p0.y + 1, static_cast<int>(std::lround((cy + h / 2) * size.height))));
    const cv::Rect box = cv::Rect(p0, p1) & cv::Rect(0, 0, size.width, size.height);
    if (box.empty()) throw ConfigError(where + "the box lies outside the image");
    boxes.push_back(box);
  }
  return boxes;
}

CalibrationExample readYoloExample(const std::string& image_path, int label_class) {
  CalibrationExample e;
  e.name = image_path;
  e.bgr = cv::imread(image_path, cv::IMREAD_COLOR);
  if (e.bgr.empty()) throw ConfigError(image_path + ": cannot read the image (missing, unreadable or not an image)");
  e.boxes = readYoloBoxes(yoloLabelPath(image_path), label_class, e.bgr.size());
  return e;
}

std::vector<std::string> imagesInFolder(const std::string& folder) {
  std::vector<std::string> out;
  if (DIR* dir = opendir(folder.c_str())) {
    while (const dirent* entry = readdir(dir)) {
      std::string name = entry->d_name;
      const size_t dot = name.find_last_of('.');
      std::string ext = dot == std::string::npos ? "" : name.substr(dot);
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (ext == ".jpg" || ext == ".jpeg" || ext == ".png") out.push_back(folder + "/" + name);
    }
    closedir(dir);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> imagesUnderFolder(const std::string& folder) {
  std::vector<std::string> images = imagesInFolder(folder);
  std::vector<std::string> folders;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    std::error_code kind_error;
    // Symlinked folders are not followed: a link back up would never end.
    if (entry.is_directory(kind_error) && !entry.is_symlink(kind_error)) folders.push_back(entry.path().string());
  }
  std::sort(folders.begin(), folders.end());
  for (const std::string& below : folders) {
    const std::vector<std::string> more = imagesUnderFolder(below);
    images.insert(images.end(), more.begin(), more.end());
  }
  return images;
}

}  // namespace rle_vision
