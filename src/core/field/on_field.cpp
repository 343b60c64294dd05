#include "rle_vision/field/on_field.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace rle_vision {

double heightAboveField(const TrackedBlob& blob, const FieldBoundaryEstimate& boundary) {
  if (!boundary.found) return std::nan("");
  return boundary.heightAbove(blob.region.cx, blob.region.bottom_at_cx);
}

void OnFieldFilter::parseNames(const std::string& text) {
  std::stringstream in(text);
  std::string name;
  while (std::getline(in, name, ',')) {
    name.erase(std::remove_if(name.begin(), name.end(), [](unsigned char c) { return std::isspace(c); }), name.end());
    if (!name.empty()) names_.push_back(name);
  }
}

std::vector<std::string> OnFieldFilter::unknownClasses(const ColorTable& table) const {
  std::vector<std::string> unknown;
  for (const std::string& name : names_) {
    const bool known = std::any_of(table.classes().begin(), table.classes().end(),
                                   [&name](const ColorClass& c) { return c.name == name; });
    if (!known) unknown.push_back(name);
  }
  return unknown;
}

int OnFieldFilter::apply(const FieldBoundaryEstimate& boundary, const ColorTable& table, std::vector<TrackedBlob>* blobs,
                         std::vector<double>* above) const {
  above->clear();
  int dropped = 0;
  size_t kept = 0;
  for (size_t i = 0; i < blobs->size(); ++i) {
    const TrackedBlob& blob = (*blobs)[i];
    const double height = heightAboveField(blob, boundary);
    const std::string& name = table.classes()[blob.region.label - 1].name;
    if (height > margin_px_ && std::find(names_.begin(), names_.end(), name) != names_.end()) {
      ++dropped;
      continue;
    }
    (*blobs)[kept++] = blob;
    above->push_back(height);
  }
  blobs->resize(kept);
  return dropped;
}

}  // namespace rle_vision
