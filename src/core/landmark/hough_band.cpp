#include "landmark/hough_band.h"

namespace rle_vision {
namespace hough {

namespace {

// Sorts by t0 a list that is a few sorted stretches one after another (a band's rows, each
// in order along the line one way or the other): each stretch is put in ascending order, then
// neighbouring stretches are merged, O(n log stretches) where std::sort would be O(n log n).
// Its buffers are kept per thread: it runs for every line candidate.
void sortStretches(std::vector<Interval>* list) {
  const auto before = [](const Interval& a, const Interval& b) { return a.t0 < b.t0; };
  thread_local std::vector<Interval> scratch;
  thread_local std::vector<size_t> bounds, merged;
  bounds.assign(1, 0);
  const size_t n = list->size();
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    if (j < n && before((*list)[j], (*list)[i])) {  // descending: reverse it
      while (j < n && !before((*list)[j - 1], (*list)[j])) ++j;
      std::reverse(list->begin() + i, list->begin() + j);
    } else {
      while (j < n && !before((*list)[j], (*list)[j - 1])) ++j;
    }
    bounds.push_back(j);
    i = j;
  }
  scratch.resize(n);
  while (bounds.size() > 2) {
    merged.assign(1, 0);
    for (size_t k = 0; k + 1 < bounds.size(); k += 2) {
      const size_t lo = bounds[k], mid = bounds[k + 1], hi = k + 2 < bounds.size() ? bounds[k + 2] : mid;
      std::merge(list->begin() + lo, list->begin() + mid, list->begin() + mid, list->begin() + hi, scratch.begin() + lo,
                 before);
      merged.push_back(hi);
    }
    list->swap(scratch);
    bounds.swap(merged);
  }
}

}  // namespace

std::vector<Interval> pieces(std::vector<Interval>* intervals, double max_gap) {
  sortStretches(intervals);
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
