// Objects known to be on the field: a blob's lowest point (below its centroid) against the
// field boundary, and the blobs of classes that must stand on the field dropped when they lie
// beyond it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rle_vision/color/color_table.h"
#include "rle_vision/field/field_boundary.h"
#include "rle_vision/tracking/blob_tracker.h"

namespace rle_vision {

// How far the blob's lowest point in its centroid's column lies above the boundary (px;
// negative: on the field side); NaN without a boundary.
double heightAboveField(const TrackedBlob& blob, const FieldBoundaryEstimate& boundary);

class OnFieldFilter {
 public:
  // `required`: the names of the classes that must stand on the field (comma-separated, spaces
  // ignored); a blob of one lying more than margin_px above the boundary is dropped.
  OnFieldFilter(const std::string& required, double margin_px) : margin_px_(margin_px) { parseNames(required); }

  // Names in `required` that `table` does not have (so the user hears of a typo).
  std::vector<std::string> unknownClasses(const ColorTable& table) const;

  // Fills `above` (per kept blob, in order) and removes the required classes' blobs beyond the
  // boundary; returns how many were dropped. Without a boundary (not found) nothing is dropped.
  int apply(const FieldBoundaryEstimate& boundary, const ColorTable& table, std::vector<TrackedBlob>* blobs,
            std::vector<double>* above) const;

  bool empty() const { return names_.empty(); }

 private:
  void parseNames(const std::string& text);
  std::vector<std::string> names_;
  double margin_px_;
};

}  // namespace rle_vision
