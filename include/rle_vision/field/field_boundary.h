// The field boundary: the line above which nothing standing on the field can be, where the
// floor meets walls, stands or the rest of the hall. Indoors it is the landmark the horizon is
// outdoors, and it tells objects on the field from the same colours beyond it.
//
// Per column, scanning up from the bottom, the top of the field is where the running score (+1 a
// field pixel, 0 a field line's: brighter than the floor and less saturated, -non_field_penalty
// any other) peaks, so field lines and short occlusions do not end it but the stands do. Field pixels: a mask's, or (from a YUV image) those near the floor's
// colour as the scan follows it up the column: a floor's colour drifts across the view
// (vignetting, a lamp's sheen on the far field), a wall's or a stand's differs at once; and
// never a pixel far greyer than the floor (shade shrinks a floor's chroma towards grey, and a
// scan must not follow it into grey walls and black robots). The columns'
// tops are median-filtered over five columns (one stray column does not lift the boundary),
// then opened: a dip narrower than max_occlusion_share of the columns (a robot or a person in
// front of the edge) is bridged by the straight line between its sides, while wider shapes
// (a corner, the bend a fisheye gives a straight edge) stay; an occluder at an end of the view,
// with no far side, shows as a step down (the field's own edge is continuous) and is held at
// the row before the step. The result is simplified to a polyline within
// inlier_px: one segment, two at a corner, more where a fisheye bends the edge. Confidence:
// the share of columns with field whose own top lies on the polyline.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"

namespace rle_vision {

// The parameters (field_column_step_px, field_inlier_px, ...) are the FIELD_BOUNDARY group of
// landmark_params.def, with their defaults and meanings.
struct FieldBoundaryOptions {
#define RLE_FIELD_BOUNDARY_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
};

// (The message is FieldBoundary.msg; this is the estimate it carries, as HorizonEstimate is Horizon.msg's.)
struct FieldBoundaryEstimate {
  bool found = false;
  double confidence = 0;               // share of the columns with field supporting the polyline
  std::vector<cv::Point2f> polyline;   // left to right, x from the first column to the last
  std::vector<cv::Point2f> column_tops;  // per scanned column with field: the top of its field

  // The boundary's row at column x (interpolated on the polyline, held flat beyond its ends);
  // NaN without a boundary.
  double rowAt(double x) const;
  // How far (px) the image point (x, y) lies above the boundary (negative: on the field side).
  double heightAbove(double x, double y) const { return rowAt(x) - y; }
};

class FieldBoundaryFinder {
 public:
  explicit FieldBoundaryFinder(const FieldBoundaryOptions& options = FieldBoundaryOptions()) : options_(options) {}

  // `field_mask`: CV_8UC1, non-zero where the field colour is.
  FieldBoundaryEstimate find(const cv::Mat& field_mask) const;
  // From the scanned columns' YUV (CV_8UC3, fieldYuvColumns: column j is image column
  // first_x + j step_x; all the scan reads) and the field colour (a YUV range): field pixels lie
  // within the range's half widths of the colour followed up the column so far (moving by
  // follow_rate per field pixel) and at least min_saturation_ratio of the range centre's
  // saturation.
  FieldBoundaryEstimate findInColumns(const cv::Mat& yuv_columns, const ColorClass& field, double first_x,
                                      double step_x) const;

  const FieldBoundaryOptions& options() const { return options_; }

 private:
  // column_top(j, &score): the top of scanned column j (image column first_x + j step).
  template <class ColumnTop>
  FieldBoundaryEstimate fromColumns(int column_count, int row_count, double first_x, double step,
                                    ColumnTop column_top) const;

  FieldBoundaryOptions options_;
};

// Bridges dips of a row profile (larger rows: lower in the image) narrower than `window`
// entries: a grey-scale opening.
void passOverOcclusions(std::vector<float>* rows, int window);
// The dips that opening bridges by more than depth_px, each replaced by the straight line
// between the columns either side of it (at an end of the profile: by the opening).
void bridgeOcclusions(std::vector<float>* rows, int window, double depth_px);
// At either end: a stretch running to the end behind a step down of more than jump_px (an
// occluder with no far side in view), at most max_share of the entries, held at the row
// before the step.
void bridgeEndOcclusions(std::vector<float>* rows, double jump_px, double max_share);
// Douglas-Peucker simplification of a polyline within `tolerance_px`.
std::vector<cv::Point2f> simplifyPolyline(const std::vector<cv::Point2f>& points, double tolerance_px);

}  // namespace rle_vision
