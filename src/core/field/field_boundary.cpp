#include "rle_vision/field/field_boundary.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rle_vision {
namespace {

double distanceToSegment(const cv::Point2f& p, const cv::Point2f& a, const cv::Point2f& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, length2 = dx * dx + dy * dy;
  double t = length2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / length2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

void simplify(const std::vector<cv::Point2f>& p, size_t first, size_t last, double tolerance,
              std::vector<cv::Point2f>* out) {
  double farthest = 0;
  size_t index = first;
  for (size_t i = first + 1; i < last; ++i) {
    const double d = distanceToSegment(p[i], p[first], p[last]);
    if (d > farthest) farthest = d, index = i;
  }
  if (farthest > tolerance) {
    simplify(p, first, index, tolerance, out);
    simplify(p, index, last, tolerance, out);
  } else {
    out->push_back(p[last]);
  }
}

// The top of the field in column x: where the running score from the bottom peaks, and that
// score (field pixels net of the penalised others below it).
double columnTop(const cv::Mat& mask, int x, double penalty, double* score) {
  double running = 0, best = 0;
  int top = mask.rows;
  for (int r = mask.rows - 1; r >= 0; --r) {
    running += mask.at<uint8_t>(r, x) ? 1.0 : -penalty;
    if (running > best) best = running, top = r;
  }
  *score = best;
  return top;
}

// The floor followed up a column: a pixel within the range's half widths of the colour
// followed so far is field, and moves that colour by follow_rate towards its own; a field line
// is neutral. Across a
// floor the colour drifts (vignetting, a lamp's sheen on the far field); a wall's or a stand's
// differs at once. A pixel far less saturated than the floor's seed colour is never floor: in
// shade a floor's chroma shrinks towards grey, and without that floor a scan could follow the
// shade into the grey and black of robots and walls.
class FollowedFloor {
 public:
  FollowedFloor(const ColorClass& range, double rate, double min_saturation_ratio) : rate_(rate) {
    for (int c = 0; c < 3; ++c) {
      centre_[c] = 0.5 * (range.min[c] + range.max[c]);
      half_[c] = 0.5 * (range.max[c] - range.min[c]);
    }
    const double seed_saturation = std::hypot(centre_[1] - 128, centre_[2] - 128);
    seed_saturation2_ = seed_saturation * seed_saturation;
    min_saturation2_ = std::pow(min_saturation_ratio * seed_saturation, 2);
  }
  double columnTop(const cv::Mat& yuv, int x, double penalty, double* score) const {
    double colour[3] = {centre_[0], centre_[1], centre_[2]};
    double running = 0, best = 0;
    int top = yuv.rows;
    for (int r = yuv.rows - 1; r >= 0; --r) {
      const uint8_t* p = yuv.ptr<uint8_t>(r) + 3 * x;
      const double u = p[1] - 128.0, v = p[2] - 128.0;
      const bool field = std::fabs(p[0] - colour[0]) <= half_[0] && std::fabs(p[1] - colour[1]) <= half_[1] &&
                         std::fabs(p[2] - colour[2]) <= half_[2] && u * u + v * v >= min_saturation2_;
      if (field) {
        for (int c = 0; c < 3; ++c) colour[c] += rate_ * (p[c] - colour[c]);
      }
      // A field line (brighter than the floor and less saturated: white, or white blurred into
      // the floor at its edges) neither extends the field nor ends it: a strip of floor beyond
      // an outer line still counts, and a white wall adds nothing.
      const bool line = !field && p[0] > colour[0] + half_[0] && u * u + v * v < seed_saturation2_;
      running += field ? 1.0 : line ? 0.0 : -penalty;
      if (running > best) best = running, top = r;
    }
    *score = best;
    return top;
  }

 private:
  double centre_[3], half_[3];
  double rate_, seed_saturation2_, min_saturation2_;
};

}  // namespace

double FieldBoundaryEstimate::rowAt(double x) const {
  if (!found || polyline.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (x <= polyline.front().x) return polyline.front().y;
  for (size_t i = 1; i < polyline.size(); ++i) {
    if (x <= polyline[i].x) {
      const cv::Point2f& a = polyline[i - 1];
      const cv::Point2f& b = polyline[i];
      return b.x > a.x ? a.y + (x - a.x) * (b.y - a.y) / (b.x - a.x) : b.y;
    }
  }
  return polyline.back().y;
}

void passOverOcclusions(std::vector<float>* rows, int window) {
  // A grey-scale opening of the rows (a closing of the field's height): the lowest row within
  // each window, then the highest of those over the windows holding a column. A dip of the
  // field top narrower than the window (a robot in front of the edge) is bridged at the height
  // of its sides; wider shapes (a corner, a fisheye's bend) stay. The profile is continued
  // beyond its ends along its end slopes, so that a slope at an end is not taken for a dip.
  const int n = static_cast<int>(rows->size()), half = window / 2;
  if (half <= 0 || n < 2) return;
  auto end_slope = [&](int first, int direction) {
    std::vector<float> steps;
    for (int k = 0; k < half && first + (k + 1) * direction >= 0 && first + (k + 1) * direction < n; ++k) {
      steps.push_back((*rows)[first + (k + 1) * direction] - (*rows)[first + k * direction]);
    }
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    return steps[steps.size() / 2];
  };
  const int pad = 2 * half;
  const float left = end_slope(0, 1), right = end_slope(n - 1, -1);
  std::vector<float> padded(n + 2 * pad);
  for (int i = 0; i < static_cast<int>(padded.size()); ++i) {
    const int k = i - pad;
    padded[i] = k < 0 ? (*rows)[0] + left * k : k >= n ? (*rows)[n - 1] - right * (k - (n - 1)) : (*rows)[k];
  }
  // Lowest row of each full window [start, start + 2 half], then per column the highest of them.
  std::vector<float> lowest(padded.size() - 2 * half);
  for (size_t start = 0; start < lowest.size(); ++start) {
    lowest[start] = *std::min_element(padded.begin() + start, padded.begin() + start + 2 * half + 1);
  }
  for (int i = 0; i < n; ++i) {
    const int column = i + pad;  // windows holding it start at column - 2 half .. column
    (*rows)[i] = *std::max_element(lowest.begin() + (column - 2 * half), lowest.begin() + column + 1);
  }
}

void bridgeOcclusions(std::vector<float>* rows, int window, double depth_px) {
  // The dips the opening bridges, joined straight from the columns either side of each (the
  // opening alone would bridge them flat, at the lower side's height, and the field edge
  // behind a robot is seldom level).
  std::vector<float> opened = *rows;
  passOverOcclusions(&opened, window);
  const int n = static_cast<int>(rows->size());
  for (int i = 0; i < n;) {
    if ((*rows)[i] - opened[i] <= depth_px) {
      ++i;
      continue;
    }
    int end = i;
    while (end < n && (*rows)[end] - opened[end] > depth_px) ++end;
    // The dip's sides are smeared over `margin` columns (the median filter): join from beyond them.
    const int margin = 2;
    const int last_end = end;
    i = std::max(0, i - margin);
    end = std::min(n, end + margin);
    for (int k = i; k < end; ++k) {
      if (i == 0 || end == n) {
        (*rows)[k] = opened[k];  // at an end of the view: no column beyond it
      } else {
        const float t = static_cast<float>(k - (i - 1)) / (end - (i - 1));
        (*rows)[k] = (1 - t) * (*rows)[i - 1] + t * (*rows)[end];
      }
    }
    i = std::max(end, last_end + 1);
  }
}

void bridgeEndOcclusions(std::vector<float>* rows, double jump_px, double max_share) {
  // At an end of the view an occluder has no far side to bridge to; it shows as a step down
  // (a jump, where the field's own edge is continuous) into a stretch that runs to the end.
  // That stretch is held at the row before the step; repeated, as occluders stand in front of
  // occluders.
  std::vector<float>& r = *rows;
  const int n = static_cast<int>(r.size()), longest = static_cast<int>(max_share * n);
  for (int direction : {1, -1}) {
    for (int round = 0; round < 8; ++round) {
      // From the end inwards, the first jump.
      int k = direction > 0 ? n - 1 : 0;
      const int step = -direction;
      while (k + step >= 0 && k + step < n && std::fabs(r[k] - r[k + step]) <= jump_px) k += step;
      const int inner = k + step, length = direction > 0 ? n - k : k + 1;
      if (inner < 0 || inner >= n || r[k] <= r[inner] || length > longest) break;
      for (int i = k; i >= 0 && i < n; i -= step) r[i] = r[inner];
    }
  }
}

std::vector<cv::Point2f> simplifyPolyline(const std::vector<cv::Point2f>& points, double tolerance_px) {
  if (points.size() <= 2) return points;
  std::vector<cv::Point2f> out = {points.front()};
  simplify(points, 0, points.size() - 1, tolerance_px, &out);
  return out;
}

FieldBoundaryEstimate FieldBoundaryFinder::find(const cv::Mat& field_mask) const {
  if (field_mask.empty() || field_mask.type() != CV_8UC1) return FieldBoundaryEstimate();
  const int step = std::max(1, options_.column_step_px), first = step / 2;
  return fromColumns((field_mask.cols - first + step - 1) / step, field_mask.rows, first, step,
                     [&](int j, double* score) {
                       return columnTop(field_mask, first + j * step, options_.non_field_penalty, score);
                     });
}

FieldBoundaryEstimate FieldBoundaryFinder::findInColumns(const cv::Mat& yuv_columns, const ColorClass& field,
                                                         double first_x, double step_x) const {
  if (yuv_columns.empty() || yuv_columns.type() != CV_8UC3) return FieldBoundaryEstimate();
  const FollowedFloor floor(field, options_.follow_rate, options_.min_saturation_ratio);
  return fromColumns(yuv_columns.cols, yuv_columns.rows, first_x, step_x, [&](int j, double* score) {
    return floor.columnTop(yuv_columns, j, options_.non_field_penalty, score);
  });
}

template <class ColumnTop>
FieldBoundaryEstimate FieldBoundaryFinder::fromColumns(int column_count, int row_count, double first_x, double step,
                                                       ColumnTop column_top) const {
  FieldBoundaryEstimate result;
  const FieldBoundaryOptions& o = options_;
  const double min_score = o.min_field_share * row_count;
  std::vector<double> xs, tops;
  int columns = 0;
  for (int j = 0; j < column_count; ++j) {
    ++columns;
    double score = 0;
    const double top = column_top(j, &score);
    const double x = first_x + j * step;
    if (score < min_score) continue;
    xs.push_back(x);
    tops.push_back(top);
  }
  if (columns == 0 || xs.size() < o.min_columns_share * columns || xs.size() < 3) return result;
  // One stray column (a green shirt above the boundary) must not lift the boundary: median of 5.
  std::vector<float> rows(xs.size());
  for (size_t i = 0; i < xs.size(); ++i) {
    const size_t lo = i < 2 ? 0 : i - 2, hi = std::min(xs.size() - 1, i + 2);
    std::vector<double> window(tops.begin() + lo, tops.begin() + hi + 1);
    std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
    rows[i] = static_cast<float>(window[window.size() / 2]);
    result.column_tops.emplace_back(static_cast<float>(xs[i]), static_cast<float>(tops[i]));
  }
  bridgeOcclusions(&rows, static_cast<int>(std::ceil(o.max_occlusion_share * columns)) | 1, o.inlier_px);
  // A continuous edge rises or falls at most about one row per column; an occluder's side jumps.
  bridgeEndOcclusions(&rows, 3.0 * step + o.inlier_px, 0.5);
  std::vector<cv::Point2f> profile;
  for (size_t i = 0; i < xs.size(); ++i) profile.emplace_back(static_cast<float>(xs[i]), rows[i]);
  result.polyline = simplifyPolyline(profile, o.inlier_px);
  result.found = true;  // for rowAt
  int supporting = 0;
  for (const cv::Point2f& p : result.column_tops) {
    if (std::fabs(result.rowAt(p.x) - p.y) <= o.inlier_px) ++supporting;
  }
  result.confidence = static_cast<double>(supporting) / result.column_tops.size();
  result.found = result.confidence >= o.min_confidence;
  if (!result.found) result.polyline.clear();
  return result;
}

}  // namespace rle_vision
