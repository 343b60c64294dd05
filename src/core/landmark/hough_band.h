// The Hough's view of one edge object (private to the core): its runs indexed by row, the
// pixels lines found so far have claimed, and scans of the object's pixels inside a band
// around a line.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "rle_vision/landmark/line_geometry.h"
#include "rle_vision/segment/run_length.h"

namespace rle_vision {
namespace hough {

// a x + b y + c = 0 with (a, b) = (-sin theta, cos theta).
struct Homogeneous {
  double a, b, c;
};

inline Homogeneous homogeneous(const ImageLine& line) {
  Homogeneous h;
  homogeneousFromLine(line, &h.a, &h.b, &h.c);
  return h;
}

// Position along the line of pixel (x, y): the direction is (cos theta, sin theta) = (b, -a).
// (Also for the accumulator's cell lines, which carry the same a, b, c.)
template <class Line>
inline double along(const Line& h, double x, double y) {
  return h.b * x - h.a * y;
}
template <class Line>
inline double distance(const Line& h, double x, double y) {
  return h.a * x + h.b * y + h.c;
}

// floor and ceil of v clamped to [lo - 1, hi + 1] (which keeps the int conversion defined):
// std::floor is a library call on baseline x86-64, and these run once per row of a band.
inline int floorWithin(double v, int lo, int hi) {
  v = std::min(std::max(v, lo - 1.0), hi + 1.0);
  const int i = static_cast<int>(v);
  return i - (v < i);
}
inline int ceilWithin(double v, int lo, int hi) {
  v = std::min(std::max(v, lo - 1.0), hi + 1.0);
  const int i = static_cast<int>(v);
  return i + (v > i);
}

// Positions along a line, [lo, hi].
struct AlongRange {
  double lo, hi;
};

// A stretch of pixels along a line: positions [t0, t1], all pixels and those no line claimed.
struct Interval {
  double t0, t1;
  double pixels;
  double free_pixels;
};

// Stretches of the line whose pixels follow each other with gaps up to max_gap (sorts
// `intervals`).
std::vector<Interval> pieces(std::vector<Interval>* intervals, double max_gap);

// Calls visit(a, b) for every maximal stretch [a, b] of [x0, x1] whose claim flags are 0.
template <class Visit>
inline void forEachUnclaimed(int x0, int x1, const uint8_t* claimed, Visit&& visit) {
  int x = x0;
  while (x <= x1) {
    while (x <= x1 && claimed[x]) ++x;
    const int start = x;
    while (x <= x1 && !claimed[x]) ++x;
    if (x > start) visit(start, x - 1);
  }
}

// One edge object's runs with an index by row, so that a band only visits the rows it can
// reach, and the pixels lines found so far have claimed (per pixel of the bounding box).
class ObjectRuns {
 public:
  ObjectRuns(const Run* runs, const int32_t* row_first, int top, int bottom, int left, int right, uint8_t* claimed)
      : runs_(runs), row_first_(row_first), top_(top), bottom_(bottom), left_(left), right_(right), claimed_(claimed) {}

  // The claim flags of row y: claimedRow(y)[x] is pixel (x, y)'s.
  const uint8_t* claimedRow(int y) const { return writableClaimedRow(y); }

  // The columns [*lo, *hi] of row y (clamped to the box give or take one) whose centres lie
  // within `half_width` of the line; *hi < *lo when none.
  void bandColumns(const Homogeneous& h, double half_width, int y, int* lo, int* hi) const;

  // Calls visit(y, x0, x1, claimed_row) for every stretch [x0, x1] of the object's pixels in
  // row y within `half_width` of the line (and, with `range`, at positions along it in the
  // range); claimed_row[x] is the claim flag of pixel (x, y) and may be written.
  template <class Visit>
  void forEachStretch(const Homogeneous& h, double half_width, const std::optional<AlongRange>& range,
                      Visit&& visit) const;

  // Marks the pixels within `half_width` of the line, at positions in `range`, as claimed.
  void claim(const Homogeneous& h, double half_width, const AlongRange& range) const {
    forEachStretch(h, half_width, range, [](int, int x0, int x1, uint8_t* row) { std::fill(row + x0, row + x1 + 1, 1); });
  }

 private:
  int stride() const { return right_ - left_ + 1; }
  uint8_t* writableClaimedRow(int y) const { return claimed_ + (y - top_) * stride() - left_; }
  void rowsOfBand(const Homogeneous& h, double half_width, const std::optional<AlongRange>& range, int* y0,
                  int* y1) const;

  const Run* runs_;
  const int32_t* row_first_;  // runs of row top + k are [row_first[k], row_first[k + 1])
  int top_, bottom_, left_, right_;
  uint8_t* claimed_;
};

template <class Visit>
void ObjectRuns::forEachStretch(const Homogeneous& h, double band, const std::optional<AlongRange>& range,
                                Visit&& visit) const {
  int y0 = 0, y1 = -1;
  rowsOfBand(h, band, range, &y0, &y1);
  // Per row, the x range the band (and the range along the line) allows; then only the runs
  // overlapping it (a row's runs are sorted by x, so the first one is found by bisection).
  // Pixels x of row y with |a x + b y + c| <= band: x in [(-band - o) / a, (band - o) / a].
  const bool level = std::fabs(h.a) < 1e-12;
  const double inv_a = level ? 0.0 : 1.0 / h.a;
  const bool across = range && std::fabs(h.b) >= 1e-12;
  const double inv_b = across ? 1.0 / h.b : 0.0;
  for (int y = y0; y <= y1; ++y) {
    int lo = left_, hi = right_;
    const double offset = h.b * y + h.c;
    if (level) {
      if (std::fabs(offset) > band) continue;
    } else {
      double e0 = (-band - offset) * inv_a, e1 = (band - offset) * inv_a;
      if (e0 > e1) std::swap(e0, e1);
      lo = std::max(lo, ceilWithin(e0 - 1e-9, left_, right_));
      hi = std::min(hi, floorWithin(e1 + 1e-9, left_, right_));
    }
    if (range) {
      // t = b x - a y is linear in x along the row.
      if (!across) {
        const double t = -h.a * y;
        if (t < range->lo || t > range->hi) continue;
      } else {
        double e0 = (range->lo + h.a * y) * inv_b, e1 = (range->hi + h.a * y) * inv_b;
        if (e0 > e1) std::swap(e0, e1);
        lo = std::max(lo, ceilWithin(e0 - 1e-9, left_, right_));
        hi = std::min(hi, floorWithin(e1 + 1e-9, left_, right_));
      }
    }
    if (lo > hi) continue;
    const Run* run_ptr = runs_ + row_first_[y - top_];
    const Run* const row_end = runs_ + row_first_[y - top_ + 1];
    if (row_end - run_ptr > 4) {
      run_ptr = std::partition_point(run_ptr, row_end, [lo](const Run& r) { return r.x1 < lo; });
    }
    uint8_t* const claimed_row = writableClaimedRow(y);
    for (; run_ptr < row_end && run_ptr->x0 <= hi; ++run_ptr) {
      if (run_ptr->x1 < lo) continue;
      visit(y, std::max(lo, static_cast<int>(run_ptr->x0)), std::min(hi, static_cast<int>(run_ptr->x1)), claimed_row);
    }
  }
}

}  // namespace hough
}  // namespace rle_vision
