#include "rle_vision/rle_hough.h"

#include <algorithm>
#include <cmath>

#include "rle_vision/ridge_fit.h"

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr uint32_t kEmpty = 0xFFFFFFFFu;
// Cells whose lines cross a found segment at up to this angle are its own noisy votes.
constexpr double kExplainedTiltDeg = 20;

struct Homogeneous {
  double a, b, c;  // a x + b y + c = 0, (a, b) = (-sin theta, cos theta)
};

Homogeneous homogeneous(const ImageLine& line) {
  Homogeneous h;
  homogeneousFromLine(line, &h.a, &h.b, &h.c);
  return h;
}

// Position along the line of pixel (x, y): the direction is (cos theta, sin theta) = (b, -a).
// (Also for the accumulator's cell lines, which carry the same a, b, c.)
template <class Line>
inline double along(const Line& h, double x, double y) { return h.b * x - h.a * y; }
template <class Line>
inline double distance(const Line& h, double x, double y) { return h.a * x + h.b * y + h.c; }

struct Interval {
  double t0, t1;
  double pixels;       // all pixels
  double free_pixels;  // pixels no line has claimed
};

// Stretches of the line whose pixels follow each other with gaps up to max_gap.
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

Interval mostPixels(const std::vector<Interval>& list) {
  Interval best{0, 0, 0, 0};
  for (const Interval& i : list) {
    if (i.pixels > best.pixels) best = i;
  }
  return best;
}

// Two segments on the same line (angle and offset within the tolerances) that overlap along
// it by at least half the shorter one.
bool sameSegment(const DetectedLine& a, const DetectedLine& b, double angle_tol, double offset_tol) {
  if (lineAngleDifference(a.line.theta, b.line.theta) > angle_tol) return false;
  if (std::fabs(signedDistance(a.line, 0.5 * (b.x1 + b.x2), 0.5 * (b.y1 + b.y2))) > offset_tol) return false;
  const double dx = std::cos(a.line.theta), dy = std::sin(a.line.theta);
  const double a0 = a.x1 * dx + a.y1 * dy, a1 = a.x2 * dx + a.y2 * dy;
  const double b0 = b.x1 * dx + b.y1 * dy, b1 = b.x2 * dx + b.y2 * dy;
  const double overlap = std::min(std::max(a0, a1), std::max(b0, b1)) - std::max(std::min(a0, a1), std::min(b0, b1));
  return overlap > 0.5 * std::min(a.length, b.length);
}

}  // namespace

// An edge object's runs with an index by row, so that a line's band only visits the rows it
// can reach, and the pixels lines found so far have claimed.
struct ObjectRuns {
  const Run* runs;
  const int32_t* row_first;  // runs of row top + k are [row_first[k], row_first[k + 1])
  int top, bottom, left, right;
  uint8_t* claimed;          // per pixel of the bounding box

  int stride() const { return right - left + 1; }
  bool isClaimed(int x, int y) const { return claimed[(y - top) * stride() + (x - left)] != 0; }

  // Rows [*y0, *y1] the band of `distance` around the line crosses inside the object's
  // bounding box (and, with `t_range`, where its positions along the line are in range).
  void rowsOfBand(const Homogeneous& h, double distance, const double* t_range, int* y0, int* y1) const {
    *y0 = top;
    *y1 = bottom;
    if (std::fabs(h.b) > 1e-3) {  // y = -(a x + c) / b, widened by distance / |b|
      const double ya = -(h.a * (left - 1) + h.c) / h.b, yb = -(h.a * (right + 1) + h.c) / h.b;
      const double reach = distance / std::fabs(h.b);
      *y0 = std::max(*y0, static_cast<int>(std::floor(std::min(ya, yb) - reach)));
      *y1 = std::min(*y1, static_cast<int>(std::ceil(std::max(ya, yb) + reach)));
    }
    if (t_range && std::fabs(h.a) > 1e-3) {  // t = b x - a y: y = (b x - t) / a at the box's corners
      double lo = 1e300, hi = -1e300;
      for (double x : {left - 1.0, right + 1.0}) {
        for (int k = 0; k < 2; ++k) {
          const double y = (h.b * x - t_range[k]) / h.a;
          lo = std::min(lo, y);
          hi = std::max(hi, y);
        }
      }
      *y0 = std::max(*y0, static_cast<int>(std::floor(lo)) - 1);
      *y1 = std::min(*y1, static_cast<int>(std::ceil(hi)) + 1);
    }
  }
};

namespace {

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

// One run's pixels [lo, hi] of row y (all of them in the band).
inline void collectRun(const ObjectRuns& object, const Homogeneous& h, int lo, int hi, int y, PointSums* sums,
                       std::vector<Interval>* intervals, bool claim, int inner_lo, int inner_hi, double* inner_count) {
  uint8_t* row = object.claimed + (y - object.top) * object.stride() - object.left;
  int free = 0;
  for (int x = lo; x <= hi; ++x) {
    if (!row[x]) {
      ++free;
      if (sums) sums->addPixel(x, y);
    }
    if (claim) row[x] = 1;
  }
  if (inner_count) {
    for (int x = std::max(lo, inner_lo); x <= std::min(hi, inner_hi); ++x) *inner_count += row[x] ? 0 : 1;
  }
  if (intervals) {
    double t0 = along(h, lo, y), t1 = along(h, hi, y);
    if (t0 > t1) std::swap(t0, t1);
    intervals->push_back({t0, t1, static_cast<double>(hi - lo + 1), static_cast<double>(free)});
  }
}

// The object's pixels within `band` of the line and, when `t_range` is given, with a position
// along the line in [t_lo, t_hi]: the sums of those no line has claimed yet, their intervals
// along the line (counting all and unclaimed pixels); `claim` then marks them claimed. With
// `inner_count`, it also counts the unclaimed pixels within `inner_band` (< band) of the line.
void collect(const ObjectRuns& object, const Homogeneous& h, double band, const double* t_range,
             PointSums* sums, std::vector<Interval>* intervals, bool claim = false, double inner_band = 0,
             double* inner_count = nullptr) {
  int y0 = 0, y1 = -1;
  object.rowsOfBand(h, band, t_range, &y0, &y1);
  // Per row, the x range the band (and t range) allows; then only the runs overlapping it (a
  // row's runs are sorted by x, so the first one is found by bisection).
  // Pixels x of row y with |a x + b y + c| <= band: x in [(-band - o) / a, (band - o) / a].
  const bool level = std::fabs(h.a) < 1e-12;
  const double inv_a = level ? 0.0 : 1.0 / h.a;
  const bool across = t_range && std::fabs(h.b) >= 1e-12;
  const double inv_b = across ? 1.0 / h.b : 0.0;
  for (int y = y0; y <= y1; ++y) {
    int lo = object.left, hi = object.right;
    int inner_lo = lo, inner_hi = hi;
    const double offset = h.b * y + h.c;
    if (level) {
      if (std::fabs(offset) > band) continue;
      if (std::fabs(offset) > inner_band) inner_hi = inner_lo - 1;
    } else {
      double e0 = (-band - offset) * inv_a, e1 = (band - offset) * inv_a;
      if (e0 > e1) std::swap(e0, e1);
      lo = std::max(lo, ceilWithin(e0 - 1e-9, object.left, object.right));
      hi = std::min(hi, floorWithin(e1 + 1e-9, object.left, object.right));
      if (inner_count) {
        double i0 = (-inner_band - offset) * inv_a, i1 = (inner_band - offset) * inv_a;
        if (i0 > i1) std::swap(i0, i1);
        inner_lo = ceilWithin(i0 - 1e-9, object.left, object.right);
        inner_hi = floorWithin(i1 + 1e-9, object.left, object.right);
      }
    }
    if (t_range) {
      // t = b x - a y is linear in x along the row.
      if (!across) {
        const double t = -h.a * y;
        if (t < t_range[0] || t > t_range[1]) continue;
      } else {
        double e0 = (t_range[0] + h.a * y) * inv_b, e1 = (t_range[1] + h.a * y) * inv_b;
        if (e0 > e1) std::swap(e0, e1);
        lo = std::max(lo, ceilWithin(e0 - 1e-9, object.left, object.right));
        hi = std::min(hi, floorWithin(e1 + 1e-9, object.left, object.right));
      }
    }
    if (lo > hi) continue;
    const Run* run_ptr = object.runs + object.row_first[y - object.top];
    const Run* const row_end = object.runs + object.row_first[y - object.top + 1];
    if (row_end - run_ptr > 4) {
      run_ptr = std::partition_point(run_ptr, row_end, [lo](const Run& r) { return r.x1 < lo; });
    }
    for (; run_ptr < row_end && run_ptr->x0 <= hi; ++run_ptr) {
      const Run& run = *run_ptr;
      if (run.x1 < lo) continue;
      collectRun(object, h, std::max(lo, static_cast<int>(run.x0)), std::min(hi, static_cast<int>(run.x1)), y,
                 sums, intervals, claim, inner_lo, inner_hi, inner_count);
    }
  }
}

}  // namespace

uint64_t RleHough::samplesFor(double object_pixels, const HoughOptions& o) {
  // eq. 2-4: p_i = n_i / p, p_ii = p_i^2, S = n / p_ii, for the shortest line wanted.
  const double line_pixels = std::min(object_pixels, o.min_line_length_px * o.edge_width_px);
  if (line_pixels <= 0) return 0;
  const double p_i = line_pixels / object_pixels;
  return static_cast<uint64_t>(std::ceil(o.sampling_margin * o.min_votes / (p_i * p_i)));
}

bool RleHough::refine(const ObjectRuns& runs, const ImageLine& seed, const HoughOptions& o,
                      const cv::Mat* edge_image, double ridge_strength, std::vector<DetectedLine>* out) const {
  // A least-squares fit on the unclaimed pixels near the seed (a coarse cell): a wide band,
  // then the fitting band, which also maps the stretches of pixels along the line.
  ImageLine line = seed;
  PointSums sums;
  double rms = 0;
  // A peak whose pixels lines already found have taken (a second peak of one of them, or
  // chance votes across them) is not worth a refit: counted in the same pass.
  double unclaimed_near = 0;
  collect(runs, homogeneous(line), 2 * o.fit_distance_px, nullptr, &sums, nullptr, false, o.fit_distance_px,
          &unclaimed_near);
  if (unclaimed_near < 0.5 * o.min_line_length_px) return false;
  if (sums.n < 0.5 * o.min_line_length_px || !sums.fitLine(&line, &rms)) return true;
  sums = PointSums();
  thread_local std::vector<Interval> intervals;  // scratch, reused (this runs per Hough peak)
  intervals.clear();
  collect(runs, homogeneous(line), o.fit_distance_px, nullptr, &sums, &intervals);
  if (sums.n < 0.5 * o.min_line_length_px || !sums.fitLine(&line, &rms)) return true;

  // Every stretch long enough gives segments (a horizon broken by obstacles gives several).
  for (const Interval& piece : pieces(&intervals, o.max_gap_px)) {
    // Too short, or mostly a line found before (its stretches span corners' claimed pixels).
    if (piece.t1 - piece.t0 < o.min_line_length_px || piece.free_pixels < 0.5 * piece.pixels) continue;
    std::vector<DetectedLine> segments;
    if (edge_image) {
      // Sub-pixel: ridge centres along the line, robustly fitted, split where they bend.
      RidgeFitOptions ridge;
      ridge.half_width_px = o.fit_distance_px;
      ridge.min_strength = ridge_strength;
      ridge.max_gap_px = o.max_gap_px;
      // Near a corner the ridge bends away: the straight stretch may fall short of the pixels'
      // extent by up to a fitting band at each end, which the segment then gets back.
      std::vector<RidgeFit> fits;
      const double reach = o.fit_distance_px;
      fitRidge(*edge_image, line, piece.t0 - 2, piece.t1 + 2, ridge, std::max(5.0, o.min_line_length_px - 2 * reach), &fits);
      for (const RidgeFit& fit : fits) {
        DetectedLine d;
        d.line = fit.line;
        d.rms = fit.rms;
        d.sums = fit.sums;
        const double dx = std::cos(fit.line.theta), dy = std::sin(fit.line.theta);
        double px, py;
        pointOnLine(fit.line, &px, &py);
        double t_start = (fit.x1 - px) * dx + (fit.y1 - py) * dy, t_end = (fit.x2 - px) * dx + (fit.y2 - py) * dy;
        if (t_start > t_end) std::swap(t_start, t_end);
        // The piece's extent along the fitted line (t relative to its point on the line).
        const double origin = px * dx + py * dy;
        t_start = std::max(t_start - reach, std::min(t_start, piece.t0 - origin));
        t_end = std::min(t_end + reach, std::max(t_end, piece.t1 - origin));
        d.x1 = px + t_start * dx;
        d.y1 = py + t_start * dy;
        d.x2 = px + t_end * dx;
        d.y2 = py + t_end * dy;
        d.length = t_end - t_start;
        segments.push_back(d);
      }
    } else {
      // Without the edge image: a least-squares fit of the stretch's run pixels.
      const double range[2] = {piece.t0 - 0.5, piece.t1 + 0.5};
      DetectedLine d;
      collect(runs, homogeneous(line), o.fit_distance_px, range, &d.sums, nullptr);
      if (d.sums.n < 2 || !d.sums.fitLine(&d.line, &d.rms)) continue;
      const Homogeneous h = homogeneous(d.line);
      std::vector<Interval> own;
      collect(runs, h, o.fit_distance_px, range, nullptr, &own);
      const Interval extent = mostPixels(pieces(&own, o.max_gap_px));
      // End points: the foot of the perpendicular from the origin plus t along the direction.
      const double fx = -h.c * h.a, fy = -h.c * h.b;
      d.x1 = fx + extent.t0 * h.b;
      d.y1 = fy - extent.t0 * h.a;
      d.x2 = fx + extent.t1 * h.b;
      d.y2 = fy - extent.t1 * h.a;
      d.length = extent.t1 - extent.t0;
      segments.push_back(d);
    }
    for (DetectedLine& d : segments) {
      const Homogeneous h = homogeneous(d.line);
      const double ta = along(h, d.x1, d.y1), tb = along(h, d.x2, d.y2);
      const double range[2] = {std::min(ta, tb) - 0.5, std::max(ta, tb) + 0.5};
      PointSums support;
      collect(runs, h, 1.5, range, &support, nullptr);
      if (d.length < o.min_line_length_px || support.n < o.min_support_ratio * d.length) continue;
      d.support = static_cast<uint32_t>(support.n);
      out->push_back(d);
    }
  }
  return true;
}

void RleHough::vote(const Run* runs, int run_count, uint64_t samples, uint64_t seed, int width, int height,
                    const HoughOptions& o) {
  // Uniform over the runs' pixels, which is the paper's "a run weighted by its length, then a
  // position in it": drawn from a flat table of the pixels.
  size_t total = 0;
  for (int i = 0; i < run_count; ++i) total += runs[i].length();
  pixels_.resize(total);
  PixelXY* pixel = pixels_.data();
  for (int i = 0; i < run_count; ++i) {
    for (int x = runs[i].x0; x <= runs[i].x1; ++x) *pixel++ = {static_cast<int16_t>(x), static_cast<int16_t>(runs[i].y)};
  }
  // Sparse accumulator: an open-addressing table of (cell key, votes), of which the first
  // `capacity` slots are used; it is kept empty between rounds by clearing the slots used.
  size_t capacity = 64;
  while (capacity < 2 * samples) capacity *= 2;
  if (table_.size() < capacity) table_.assign(capacity, Cell{kEmpty, 0});
  occupied_.clear();
  theta_bins_ = static_cast<int>(std::ceil(180.0 / o.theta_bin_deg));
  alpha_ = -std::max(width, height);
  intercept_bins_ = static_cast<int>(std::ceil((width + height - alpha_) / o.intercept_bin_px)) + 1;

  uint64_t state = seed;
  auto random64 = [&state]() {  // splitmix64
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  // 64 random bits to a pixel: multiply-shift into [0, total).
  const PixelXY* const table = pixels_.data();
  auto pick = [table, total](uint64_t bits) {
    return table[static_cast<size_t>((static_cast<unsigned __int128>(bits) * total) >> 64)];
  };
  // Squared distances of pixels (coordinates < 2^13) fit an int; so does the capped limit.
  const int min_d2 = static_cast<int>(std::ceil(std::min(1e9, o.min_pair_distance_px * o.min_pair_distance_px)));
  const double per_theta_bin = 1.0 / o.theta_bin_deg, per_intercept_bin = 1.0 / o.intercept_bin_px;
  constexpr double kRadToDeg = 180.0 / M_PI;
  keys_.clear();
  for (uint64_t s = 0; s < samples; ++s) {
    // A second pixel too close to the first is redrawn (up to twice).
    const PixelXY p1 = pick(random64());
    PixelXY p2 = pick(random64());
    int dx = p2.x - p1.x, dy = p2.y - p1.y;
    for (int attempt = 1; attempt < 3 && dx * dx + dy * dy < min_d2; ++attempt) {
      p2 = pick(random64());
      dx = p2.x - p1.x;
      dy = p2.y - p1.y;
    }
    if (dx * dx + dy * dy < min_d2 || (dx == 0 && dy == 0)) continue;
    // The pair's line: theta in (-90, 90] deg, and the intercept the paper's convention picks,
    // both from one ratio r in [0, 1] (atan by a polynomial within 0.01 deg, the slope without
    // tan). Selects rather than branches: the cases come in random order.
    const bool flip = dx < 0 || (dx == 0 && dy < 0);
    dx = flip ? -dx : dx;
    dy = flip ? -dy : dy;
    const int ady = dy < 0 ? -dy : dy;
    const bool steep = ady > dx;
    const double r = static_cast<double>(steep ? dx : ady) / static_cast<double>(steep ? ady : dx);
    const double r2 = r * r;
    const double atan_deg = r * (0.9998660 + r2 * (-0.3302995 + r2 * (0.1801410 + r2 * (-0.0851330 + r2 * 0.0208351)))) * kRadToDeg;
    const double abs_deg = steep ? 90.0 - atan_deg : atan_deg;
    const double deg = dy < 0 ? -abs_deg : abs_deg;
    const double signed_r = dy < 0 ? -r : r;
    // y-intercept y1 - x1 dy/dx below 45 deg, x-intercept x1 - y1 dx/dy from there.
    const bool y_intercept = ady < dx;
    const double u = y_intercept ? p1.y : p1.x, v = y_intercept ? p1.x : p1.y;
    const double intercept = u - v * signed_r;
    int theta_bin = static_cast<int>((deg + 90.0) * per_theta_bin);
    if (theta_bin >= theta_bins_) theta_bin -= theta_bins_;  // +90 deg is -90 deg
    const int intercept_bin = std::min(intercept_bins_ - 1, std::max(0, floorWithin((intercept - alpha_) * per_intercept_bin, 0, intercept_bins_ - 1)));
    keys_.push_back(static_cast<uint32_t>(theta_bin) * static_cast<uint32_t>(intercept_bins_) + static_cast<uint32_t>(intercept_bin));
  }
  // Then the votes (apart from the draws, whose divisions overlap when nothing waits on the
  // table).
  for (const uint32_t key : keys_) {
    size_t slot = (key * 2654435761u) & (capacity - 1);
    while (table_[slot].key != kEmpty && table_[slot].key != key) slot = (slot + 1) & (capacity - 1);
    if (table_[slot].key == kEmpty) {
      table_[slot].key = key;
      occupied_.push_back(static_cast<uint32_t>(slot));
    }
    ++table_[slot].votes;
  }
  // Cells in theta-bin order (a counting sort; within a bin, in the order the cells were
  // first voted for: deterministic), and the table emptied again.
  bucket_start_.assign(theta_bins_ + 1, 0);
  for (uint32_t slot : occupied_) ++bucket_start_[table_[slot].key / intercept_bins_ + 1];
  for (int b = 0; b < theta_bins_; ++b) bucket_start_[b + 1] += bucket_start_[b];
  cells_.resize(occupied_.size());
  fill_.assign(bucket_start_.begin(), bucket_start_.end() - 1);
  for (uint32_t slot : occupied_) {
    Cell& c = table_[slot];
    cells_[fill_[c.key / intercept_bins_]++] = c;
    c = Cell{kEmpty, 0};
  }
}

int RleHough::extractLines(const ObjectRuns& indexed, const EdgeObject& object, int index, const HoughOptions& o,
                           const cv::Mat* edge_image, double ridge_strength, std::vector<DetectedLine>* found,
                           HoughStats* stats) {
  const size_t n = cells_.size();
  const std::vector<int>& bucket_start = bucket_start_;
  // Each theta bin's line angle and normal, computed when the binning changes.
  if (static_cast<int>(bin_theta_.size()) != theta_bins_ || bins_for_deg_ != o.theta_bin_deg) {
    bins_for_deg_ = o.theta_bin_deg;
    bin_theta_.resize(theta_bins_);
    bin_normal_x_.resize(theta_bins_);
    bin_normal_y_.resize(theta_bins_);
    for (int b = 0; b < theta_bins_; ++b) {
      bin_theta_[b] = normalizeLineAngle((-90.0 + (b + 0.5) * o.theta_bin_deg) * kDeg);
      bin_normal_x_[b] = -std::sin(bin_theta_[b]);
      bin_normal_y_[b] = std::cos(bin_theta_[b]);
    }
  }
  cell_lines_.resize(n);
  std::vector<HoughCellLine>& cell_h = cell_lines_;
  for (size_t i = 0; i < n; ++i) {
    const int tb = static_cast<int>(cells_[i].key / intercept_bins_), cb = static_cast<int>(cells_[i].key % intercept_bins_);
    HoughCellLine& cell = cell_h[i];
    cell.theta = bin_theta_[tb];
    const double intercept = alpha_ + (cb + 0.5) * o.intercept_bin_px;
    // c from the intercept point: (0, intercept) or (intercept, 0).
    cell.a = bin_normal_x_[tb];
    cell.b = bin_normal_y_[tb];
    cell.c = usesYIntercept(cell.theta) ? -cell.b * intercept : -cell.a * intercept;
  }
  // Seeds: cells with two votes or more, strongest first (a single vote may still join a
  // stronger cell's window).
  std::vector<uint32_t>& order = order_;
  order.clear();
  for (size_t i = 0; i < n; ++i) {
    if (cells_[i].votes >= 2) order.push_back(static_cast<uint32_t>(i));
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return cells_[a].votes != cells_[b].votes ? cells_[a].votes > cells_[b].votes : cells_[a].key < cells_[b].key;
  });

  // Near-neighbour grouping: the strongest free cell gathers the free cells whose lines are
  // within the window of its own (so +-90 deg and the +45 deg intercept flip are no borders).
  std::vector<char>& used = used_;
  used.assign(n, 0);
  const int window_bins = static_cast<int>(std::ceil(o.peak_angle_deg / o.theta_bin_deg));
  const double cos_peak = std::cos(o.peak_angle_deg * kDeg);
  const double cos_explained = std::cos(kExplainedTiltDeg * kDeg);
  int failures = 0, added = 0;
  // Cells whose lines differ from a segment's by more than kExplainedTiltDeg cannot be
  // explained by it: only the theta bins within that (and a bin) are visited.
  const int explained_bins = static_cast<int>(std::ceil(kExplainedTiltDeg / o.theta_bin_deg)) + 1;
  const bool all_bins = 2 * explained_bins + 1 >= theta_bins_;
  const int first_bin = all_bins ? 0 : -explained_bins, last_bin = all_bins ? theta_bins_ - 1 : explained_bins;
  std::vector<uint32_t>& members = members_;
  for (uint32_t seed_index : order) {
    if (used[seed_index]) continue;
    // Peaks come strongest first: once max_failed_peaks in a row lead nowhere, the rest are
    // chance alignments of pixels from different edges.
    if (static_cast<int>(found->size()) >= o.max_lines_per_object || failures >= o.max_failed_peaks) break;
    const HoughCellLine& hs = cell_h[seed_index];
    // The foot of the object's centroid on the seed line: offsets are measured there.
    const double d0 = distance(hs, object.cx, object.cy);
    const double qx = object.cx - d0 * hs.a, qy = object.cy - d0 * hs.b;
    const int seed_bin = static_cast<int>(cells_[seed_index].key / intercept_bins_);
    uint32_t votes = 0;
    double weighted_offset = 0, weighted_angle = 0;
    members.clear();
    for (int db = -window_bins; db <= window_bins; ++db) {
      const int bin = ((seed_bin + db) % theta_bins_ + theta_bins_) % theta_bins_;
      for (int i = bucket_start[bin]; i < bucket_start[bin + 1]; ++i) {
        if (used[i]) continue;
        const double cosine = cell_h[i].a * hs.a + cell_h[i].b * hs.b;  // cos of the angle between normals
        if (std::fabs(cosine) < cos_peak) continue;
        const double angle = normalizeLineAngle(cell_h[i].theta - hs.theta);
        // Lines of opposite orientation have opposite normals: measure along the seed's.
        const double offset = distance(cell_h[i], qx, qy);
        const double signed_offset = cosine >= 0 ? offset : -offset;
        if (std::fabs(signed_offset) > o.peak_distance_px) continue;
        members.push_back(i);
        votes += cells_[i].votes;
        weighted_offset += cells_[i].votes * signed_offset;
        weighted_angle += cells_[i].votes * angle;
      }
    }
    if (static_cast<int>(votes) < o.min_votes) {
      used[seed_index] = 1;
      ++failures;
      continue;
    }
    for (size_t i : members) used[i] = 1;
    ++stats->candidates;
    // Start from the vote-weighted mean of the group.
    const ImageLine start = lineThroughPointWithAngle(qx + weighted_offset / votes * hs.a,
                                                      qy + weighted_offset / votes * hs.b,
                                                      hs.theta + weighted_angle / votes);
    refined_.clear();
    if (!refine(indexed, start, o, edge_image, ridge_strength, &refined_)) {
      ++failures;  // its pixels were taken
      continue;
    }
    ++stats->refinements;
    if (refined_.empty()) {
      ++failures;
      continue;
    }
    failures = 0;
    for (DetectedLine& line : refined_) {
      // The ridge fit follows the edge image, where claims do not hold: a segment may land on
      // one found before (collinear but apart is another segment). Keep the better supported.
      const auto same = std::find_if(found->begin(), found->end(), [&](const DetectedLine& f) {
        return sameSegment(f, line, o.peak_angle_deg * kDeg, o.peak_distance_px);
      });
      line.votes = votes;
      line.object = index;
      if (same != found->end()) {
        if (line.support > same->support) *same = line;
        continue;
      }
      found->push_back(line);
      ++added;
      // Claim the segment's pixels: later peaks and rounds work on what is left.
      const Homogeneous hl = homogeneous(line.line);
      const double ta = along(hl, line.x1, line.y1), tb = along(hl, line.x2, line.y2);
      const double range[2] = {std::min(ta, tb), std::max(ta, tb)};
      collect(indexed, hl, o.fit_distance_px, range, nullptr, nullptr, /*claim=*/true);
      // Retire the cells the segment explains: pairs drawn along its ridge vote for lines
      // tilted through it, which would otherwise seed it again. They cross it inside; an edge
      // meeting it at a corner crosses at an end, so the ends are left out.
      const double end_margin = std::min(2 * o.fit_distance_px, 0.25 * (range[1] - range[0]));
      const double inside[2] = {range[0] + end_margin, range[1] - end_margin};
      const int line_bin = std::min(theta_bins_ - 1, std::max(0, static_cast<int>((line.line.theta / kDeg + 90.0) / o.theta_bin_deg)));
      for (int db = first_bin; db <= last_bin; ++db) {
        const int bin = all_bins ? db : ((line_bin + db) % theta_bins_ + theta_bins_) % theta_bins_;
        for (int i = bucket_start[bin]; i < bucket_start[bin + 1]; ++i) {
          const HoughCellLine& hc = cell_h[i];
          if (used[i] || std::fabs(hc.a * hl.a + hc.b * hl.b) < cos_explained) continue;
          const double det = hl.a * hc.b - hl.b * hc.a;
          if (std::fabs(det) < 1e-9) {  // parallel: near enough?
            if (std::fabs(distance(hc, 0.5 * (line.x1 + line.x2), 0.5 * (line.y1 + line.y2))) <= o.fit_distance_px) used[i] = 1;
            continue;
          }
          // Where the cell's line crosses the segment's line.
          const double x = (hl.b * hc.c - hc.b * hl.c) / det, y = (hc.a * hl.c - hl.a * hc.c) / det;
          const double t = along(hl, x, y);
          if (t >= inside[0] && t <= inside[1]) used[i] = 1;
        }
      }
    }
  }
  return added;
}

void RleHough::detectInObject(const EdgeObjectFinder& edges, int index, int width, int height,
                              const HoughOptions& o, std::vector<DetectedLine>* lines, HoughStats* stats,
                              const cv::Mat* edge_image, double ridge_strength) {
  const EdgeObject& object = edges.objects()[index];
  if (object.pixels < o.min_line_length_px) return;  // too small to hold a line of that length
  const Run* runs = edges.runs().data() + object.first_run;
  ++stats->objects;
  row_first_.assign(static_cast<size_t>(object.bottom - object.top) + 2, 0);
  for (int i = 0; i < object.run_count; ++i) ++row_first_[runs[i].y - object.top + 1];
  for (size_t k = 1; k < row_first_.size(); ++k) row_first_[k] += row_first_[k - 1];
  claimed_.assign(static_cast<size_t>(object.right - object.left + 1) * (object.bottom - object.top + 1), 0);
  const ObjectRuns indexed{runs, row_first_.data(), object.top, object.bottom, object.left, object.right, claimed_.data()};

  std::vector<DetectedLine> found;
  sample_runs_.assign(runs, runs + object.run_count);
  for (int round = 0; round < o.max_rounds; ++round) {
    uint64_t pixels = 0;
    for (const Run& run : sample_runs_) pixels += run.length();
    if (pixels < o.min_line_length_px) break;
    // eq. 2-4 for the pixels still unexplained, capped.
    const uint64_t samples = std::min<uint64_t>(samplesFor(static_cast<double>(pixels), o), o.max_samples_per_object);
    stats->sample_pairs += samples;
    vote(sample_runs_.data(), static_cast<int>(sample_runs_.size()), samples,
         o.seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(index) * 8 + round + 1, width, height, o);
    if (extractLines(indexed, object, index, o, edge_image, ridge_strength, &found, stats) == 0) break;
    // The next round samples only pixels no line has claimed: the object's runs cut at them.
    sample_runs_.clear();
    for (int i = 0; i < object.run_count; ++i) {
      const Run& run = runs[i];
      int start = -1;
      for (int x = run.x0; x <= run.x1 + 1; ++x) {
        const bool free = x <= run.x1 && !indexed.isClaimed(x, run.y);
        if (free && start < 0) start = x;
        if (!free && start >= 0) {
          sample_runs_.push_back(Run{start, x - 1, run.y, 0, run.label});
          start = -1;
        }
      }
    }
  }
  lines->insert(lines->end(), found.begin(), found.end());
}

void RleHough::detect(const EdgeObjectFinder& edges, int width, int height, const HoughOptions& o,
                      std::vector<DetectedLine>* lines, HoughStats* stats, const cv::Mat* edge_image,
                      double ridge_strength) {
  lines->clear();
  *stats = HoughStats();
  for (int i = 0; i < static_cast<int>(edges.objects().size()); ++i) {
    detectInObject(edges, i, width, height, o, lines, stats, edge_image, ridge_strength);
  }
  // The paper's comparison: one global random Hough over every edge pixel needs eq. 4's pairs
  // for the shortest line among all of them.
  uint64_t all_pixels = 0;
  for (const EdgeObject& object : edges.objects()) all_pixels += object.pixels;
  stats->global_sample_pairs = samplesFor(static_cast<double>(all_pixels), o);
}

}  // namespace rle_vision
