#include "landmark/hough_band.h"

namespace rle_vision {
namespace hough {

std::vector<Interval> pieces(std::vector<Interval>* intervals, double max_gap) {
  // Rows are visited in order, so the intervals mostly come sorted one way or the other.
  const auto before = [](const Interval& a, const Interval& b) { return a.t0 < b.t0; };
  if (std::is_sorted(intervals->rbegin(), intervals->rend(), before)) std::reverse(intervals->begin(), intervals->end());
  if (!std::is_sorted(intervals->begin(), intervals->end(), before)) std::sort(intervals->begin(), intervals->end(), before);
  std::vector<Interval> out;
  for (const Interval& i : *intervals) {
    if (!out.empty() && i.t0 - out.back().t1 <= max_gap) {
      out.back().t1 = std::max(out.back().t1, i.t1);
      out.back().pixels += i.pixels;
      out.back().free_pixels += i.free_pixels;
    } else {
      out.push_back(i);
    }
  }
  return out;
}

void ObjectRuns::bandColumns(const Homogeneous& h, double half_width, int y, int* lo, int* hi) const {
  const double offset = h.b * y + h.c;
  if (std::fabs(h.a) < 1e-12) {  // level: the whole row or none of it
    *lo = left_;
    *hi = std::fabs(offset) > half_width ? left_ - 1 : right_;
    return;
  }
  const double inv_a = 1.0 / h.a;
  double i0 = (-half_width - offset) * inv_a, i1 = (half_width - offset) * inv_a;
  if (i0 > i1) std::swap(i0, i1);
  *lo = ceilWithin(i0 - 1e-9, left_, right_);
  *hi = floorWithin(i1 + 1e-9, left_, right_);
}

void ObjectRuns::rowsOfBand(const Homogeneous& h, double distance, const std::optional<AlongRange>& range, int* y0,
                            int* y1) const {
  *y0 = top_;
  *y1 = bottom_;
  if (std::fabs(h.b) > 1e-3) {  // y = -(a x + c) / b, widened by distance / |b|
    const double ya = -(h.a * (left_ - 1) + h.c) / h.b, yb = -(h.a * (right_ + 1) + h.c) / h.b;
    const double reach = distance / std::fabs(h.b);
    *y0 = std::max(*y0, static_cast<int>(std::floor(std::min(ya, yb) - reach)));
    *y1 = std::min(*y1, static_cast<int>(std::ceil(std::max(ya, yb) + reach)));
  }
  if (range && std::fabs(h.a) > 1e-3) {  // t = b x - a y: y = (b x - t) / a at the box's corners
    double lo = 1e300, hi = -1e300;
    for (double x : {left_ - 1.0, right_ + 1.0}) {
      for (double t : {range->lo, range->hi}) {
        const double y = (h.b * x - t) / h.a;
        lo = std::min(lo, y);
        hi = std::max(hi, y);
      }
    }
    *y0 = std::max(*y0, static_cast<int>(std::floor(lo)) - 1);
    *y1 = std::min(*y1, static_cast<int>(std::ceil(hi)) + 1);
  }
}

}  // namespace hough
}  // namespace rle_vision
