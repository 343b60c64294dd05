// The JSON rle_vision_detect prints for an image: blobs, lines, the horizon and the field boundary.
#pragma once

#include <string>
#include <vector>

#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/field/field_detector.h"
#include "rle_vision/landmark/landmark_detector.h"

namespace rle_vision {

// A JSON string literal of `s` (quoted, escaped).
std::string jsonString(const std::string& s);

// One image's result as a JSON object on one line (angles in radians, image coordinates);
// with `ranges_in_use`, also the colour ranges the blobs were found with ("ranges").
std::string detectionJson(const std::string& file, int width, int height, const std::vector<TrackedBlob>& blobs,
                          const ColorTable& table, const LandmarkResult& result, const FieldResult& field,
                          bool ranges_in_use = false);

// {"file": ..., "error": ...}
std::string errorJson(const std::string& file, const std::string& error);

}  // namespace rle_vision
