// YOLO label files (one per image, beside it: IMAGE.txt with lines 'class cx cy w h', all
// normalised to the image size), as used by the calibration CLI and the ball evaluation.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/learning/color_calibration.h"

namespace rle_vision {

// The label file of an image: the same path with .txt for its extension.
std::string yoloLabelPath(const std::string& image_path);

// The boxes of `label_class` in `label_path`, in pixels of an image of `size`, clamped to it
// (normalised boxes round to a pixel past the border; a box is at least 1 px). No file means
// no boxes (YOLO's convention for an image without objects). Throws ConfigError with the file
// and line for a malformed line, an empty box or a box wholly outside the image.
std::vector<cv::Rect> readYoloBoxes(const std::string& label_path, int label_class, const cv::Size& size);

// An image and its boxes of `label_class` as a calibration example. Throws ConfigError for an
// unreadable image or label file (readYoloBoxes).
CalibrationExample readYoloExample(const std::string& image_path, int label_class);

// The .jpg, .jpeg and .png files of a folder, sorted by name (empty when it cannot be read).
std::vector<std::string> imagesInFolder(const std::string& folder);
// The same for a folder and every folder below it: its own images first, then each subfolder's
// in name order (a data set's dates, recordings, ...); symlinked folders are not followed.
std::vector<std::string> imagesUnderFolder(const std::string& folder);

}  // namespace rle_vision
