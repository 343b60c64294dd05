#include "rle_vision/landmark/rle_hough.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "landmark/hough_accumulator.h"
#include "landmark/hough_band.h"
#include "rle_vision/landmark/ridge_fit.h"

namespace rle_vision {

using hough::along;
using hough::AlongRange;
using hough::distance;
using hough::homogeneous;
using hough::Homogeneous;
using hough::Interval;
using hough::ObjectRuns;

namespace {

constexpr double kDeg = M_PI / 180;
// Cells whose lines cross a found segment at up to this angle are its own noisy votes.
constexpr double kExplainedTiltDeg = 20;

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

// The sums of the object's unclaimed pixels within `half_width` of the line (and in `range`).
PointSums unclaimedSums(const ObjectRuns& runs, const Homogeneous& h, double half_width,
                        const std::optional<AlongRange>& range) {
  PointSums sums;
  runs.forEachStretch(h, half_width, range, [&sums](int y, int x0, int x1, const uint8_t* claimed) {
    hough::forEachUnclaimed(x0, x1, claimed, [&](int a, int b) { sums.addRun(a, b, y); });
  });
  return sums;
}

// The stretches of the object's pixels within `half_width` of the line (and in `range`) as
// intervals along it (all and unclaimed pixels); `unclaimed` receives the unclaimed ones' sums.
void bandIntervals(const ObjectRuns& runs, const Homogeneous& h, double half_width,
                   const std::optional<AlongRange>& range, std::vector<Interval>* intervals, PointSums* unclaimed) {
  runs.forEachStretch(h, half_width, range, [&](int y, int x0, int x1, const uint8_t* claimed) {
    int free = 0;
    hough::forEachUnclaimed(x0, x1, claimed, [&](int a, int b) {
      free += b - a + 1;
      unclaimed->addRun(a, b, y);
    });
    double t0 = along(h, x0, y), t1 = along(h, x1, y);
    if (t0 > t1) std::swap(t0, t1);
    intervals->push_back({t0, t1, static_cast<double>(x1 - x0 + 1), static_cast<double>(free)});
  });
}

// The accumulator's neighbourhood of a seed cell, and which cells a found segment explains.
struct Windows {
  int peak_bins;         // theta bins either side of a seed that may join its peak
  double cos_peak;       // cos of peak_angle_deg
  double cos_explained;  // cos of kExplainedTiltDeg
  int first_bin, last_bin;  // theta bins (relative to a segment's) its explained cells lie in
  bool all_bins;            // ... or every bin
  Windows(const HoughOptions& o, int theta_bins) {
    peak_bins = static_cast<int>(std::ceil(o.peak_angle_deg / o.theta_bin_deg));
    cos_peak = std::cos(o.peak_angle_deg * kDeg);
    cos_explained = std::cos(kExplainedTiltDeg * kDeg);
    // Cells whose lines differ from a segment's by more than kExplainedTiltDeg cannot be
    // explained by it: only the theta bins within that (and a bin) are visited.
    const int explained_bins = static_cast<int>(std::ceil(kExplainedTiltDeg / o.theta_bin_deg)) + 1;
    all_bins = 2 * explained_bins + 1 >= theta_bins;
    first_bin = all_bins ? 0 : -explained_bins;
    last_bin = all_bins ? theta_bins - 1 : explained_bins;
  }
};

// A group of neighbouring cells around a seed: its votes and the line to refine.
struct Peak {
  uint32_t votes = 0;
  ImageLine start;
};

}  // namespace

// How segments get their final fit: on the edge image's ridges, or (empty image) on run pixels.
struct Refinement {
  cv::Mat edge_image;
  double ridge_strength = 0;
};

struct RleHough::Impl {
  hough::Accumulator accumulator;
  RidgeFitter ridge_fitter;
  std::vector<int32_t> row_first;
  std::vector<uint8_t> claimed;
  std::vector<Run> sample_runs;
  std::vector<uint32_t> order, members, by_size;
  std::vector<char> used;  // per cell: grouped or retired
  std::vector<Interval> intervals;
  std::vector<RidgeFit> fits;
  std::vector<DetectedLine> refined;

  void detect(const EdgeObjectFinder& edges, int width, int height, const HoughOptions& o, const Refinement& how,
              std::vector<DetectedLine>* lines, HoughStats* stats);
  void detectInObject(const EdgeObjectFinder& edges, int index, int width, int height, const HoughOptions& o,
                      const Refinement& how, std::vector<DetectedLine>* lines, HoughStats* stats);
  void unclaimedRuns(const Run* runs, int run_count, const ObjectRuns& indexed);
  int extractLines(const ObjectRuns& runs, const EdgeObject& object, int index, const HoughOptions& o,
                   const Refinement& how, std::vector<DetectedLine>* found, HoughStats* stats);
  void orderSeeds();
  bool groupPeak(uint32_t seed_index, const EdgeObject& object, const HoughOptions& o, const Windows& windows,
                 Peak* peak);
  int keepRefined(const ObjectRuns& runs, const Peak& peak, int index, const HoughOptions& o,
                  const Windows& windows, std::vector<DetectedLine>* found);
  void retireExplained(const DetectedLine& line, const AlongRange& range, const HoughOptions& o,
                       const Windows& windows);
  bool refine(const ObjectRuns& runs, const ImageLine& seed, const HoughOptions& o, const Refinement& how,
              std::vector<DetectedLine>* out);
  void ridgeSegments(const ImageLine& line, const Interval& piece, const HoughOptions& o, const Refinement& how,
                     std::vector<DetectedLine>* segments);
  static bool runSegment(const ObjectRuns& runs, const ImageLine& line, const Interval& piece, const HoughOptions& o,
                         DetectedLine* segment);
};

RleHough::RleHough() : impl_(std::make_unique<Impl>()) {}
RleHough::~RleHough() = default;
RleHough::RleHough(RleHough&&) noexcept = default;
RleHough& RleHough::operator=(RleHough&&) noexcept = default;

uint64_t RleHough::samplesFor(double object_pixels, const HoughOptions& o) {
  // eq. 2-4: p_i = n_i / p, p_ii = p_i^2, S = n / p_ii, for the shortest line wanted.
  const double line_pixels = std::min(object_pixels, o.min_line_length_px * o.edge_width_px);
  if (line_pixels <= 0) return 0;
  const double p_i = line_pixels / object_pixels;
  return static_cast<uint64_t>(std::ceil(o.sampling_margin * o.min_votes / (p_i * p_i)));
}

void RleHough::detect(const EdgeObjectFinder& edges, const cv::Mat& edge_image, double ridge_strength,
                      const HoughOptions& options, std::vector<DetectedLine>* lines, HoughStats* stats) {
  impl_->detect(edges, edge_image.cols, edge_image.rows, options, Refinement{edge_image, ridge_strength}, lines, stats);
}

void RleHough::detectOnRuns(const EdgeObjectFinder& edges, int width, int height, const HoughOptions& options,
                            std::vector<DetectedLine>* lines, HoughStats* stats) {
  impl_->detect(edges, width, height, options, Refinement{}, lines, stats);
}

void RleHough::Impl::detect(const EdgeObjectFinder& edges, int width, int height, const HoughOptions& o,
                            const Refinement& how, std::vector<DetectedLine>* lines, HoughStats* stats) {
  lines->clear();
  *stats = HoughStats();
  // Largest objects first, so that a frame's budget goes to the longest lines; the lines come
  // out in the objects' order, as if visited in it (each object's lines do not depend on others).
  const std::vector<EdgeObject>& objects = edges.objects();
  by_size.resize(objects.size());
  for (size_t i = 0; i < by_size.size(); ++i) by_size[i] = static_cast<uint32_t>(i);
  std::stable_sort(by_size.begin(), by_size.end(),
                   [&objects](uint32_t a, uint32_t b) { return objects[a].pixels > objects[b].pixels; });
  for (const uint32_t i : by_size) {
    if (objects[i].pixels < o.min_line_length_px) continue;  // too small to hold a line of that length
    if (stats->budget_exhausted) {
      ++stats->objects_skipped;
      continue;
    }
    detectInObject(edges, static_cast<int>(i), width, height, o, how, lines, stats);
  }
  std::stable_sort(lines->begin(), lines->end(),
                   [](const DetectedLine& a, const DetectedLine& b) { return a.object < b.object; });
  // The paper's comparison: one global random Hough over every edge pixel needs eq. 4's pairs
  // for the shortest line among all of them.
  uint64_t all_pixels = 0;
  for (const EdgeObject& object : edges.objects()) all_pixels += object.pixels;
  stats->global_sample_pairs = samplesFor(static_cast<double>(all_pixels), o);
}

void RleHough::Impl::detectInObject(const EdgeObjectFinder& edges, int index, int width, int height,
                                    const HoughOptions& o, const Refinement& how, std::vector<DetectedLine>* lines,
                                    HoughStats* stats) {
  const EdgeObject& object = edges.objects()[index];
  const Run* runs = edges.runs().data() + object.first_run;
  ++stats->objects;
  row_first.assign(static_cast<size_t>(object.bottom - object.top) + 2, 0);
  for (int i = 0; i < object.run_count; ++i) ++row_first[runs[i].y - object.top + 1];
  for (size_t k = 1; k < row_first.size(); ++k) row_first[k] += row_first[k - 1];
  claimed.assign(static_cast<size_t>(object.right - object.left + 1) * (object.bottom - object.top + 1), 0);
  const ObjectRuns indexed(runs, row_first.data(), object.top, object.bottom, object.left, object.right, claimed.data());

  std::vector<DetectedLine> found;
  sample_runs.assign(runs, runs + object.run_count);
  for (int round = 0; round < o.max_rounds; ++round) {
    uint64_t pixels = 0;
    for (const Run& run : sample_runs) pixels += run.length();
    if (pixels < o.min_line_length_px) break;
    // eq. 2-4 for the pixels still unexplained, capped.
    const uint64_t samples = std::min<uint64_t>(samplesFor(static_cast<double>(pixels), o), o.max_samples_per_object);
    stats->sample_pairs += samples;
    accumulator.vote(sample_runs.data(), static_cast<int>(sample_runs.size()), samples,
                     o.seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(index) * 8 + round + 1, width, height, o);
    if (extractLines(indexed, object, index, o, how, &found, stats) == 0 || stats->budget_exhausted) break;
    unclaimedRuns(runs, object.run_count, indexed);
  }
  lines->insert(lines->end(), found.begin(), found.end());
}

void RleHough::Impl::unclaimedRuns(const Run* runs, int run_count, const ObjectRuns& indexed) {
  // The next round samples only pixels no line has claimed: the object's runs cut at them.
  sample_runs.clear();
  for (int i = 0; i < run_count; ++i) {
    const Run& run = runs[i];
    hough::forEachUnclaimed(run.x0, run.x1, indexed.claimedRow(run.y),
                            [&](int a, int b) { sample_runs.push_back(Run{a, b, run.y, 0, run.label}); });
  }
}

int RleHough::Impl::extractLines(const ObjectRuns& runs, const EdgeObject& object, int index, const HoughOptions& o,
                                 const Refinement& how, std::vector<DetectedLine>* found, HoughStats* stats) {
  orderSeeds();
  used.assign(accumulator.cells().size(), 0);
  const Windows windows(o, accumulator.thetaBins());
  int failures = 0, added = 0;
  for (uint32_t seed_index : order) {
    if (used[seed_index]) continue;
    // Peaks come strongest first: once max_failed_peaks in a row lead nowhere, the rest are
    // chance alignments of pixels from different edges.
    if (static_cast<int>(found->size()) >= o.max_lines_per_object || failures >= o.max_failed_peaks) break;
    Peak peak;
    if (!groupPeak(seed_index, object, o, windows, &peak)) {
      used[seed_index] = 1;
      ++failures;
      continue;
    }
    if (stats->candidates >= static_cast<uint64_t>(o.max_refinements_per_frame)) {
      stats->budget_exhausted = true;
      break;
    }
    ++stats->candidates;
    refined.clear();
    if (!refine(runs, peak.start, o, how, &refined)) {
      ++failures;  // its pixels were taken
      continue;
    }
    ++stats->refinements;
    if (refined.empty()) {
      ++failures;
      continue;
    }
    failures = 0;
    added += keepRefined(runs, peak, index, o, windows, found);
  }
  return added;
}

void RleHough::Impl::orderSeeds() {
  // Seeds: cells with two votes or more, strongest first (a single vote may still join a
  // stronger cell's window).
  const std::vector<hough::Cell>& cells = accumulator.cells();
  order.clear();
  for (size_t i = 0; i < cells.size(); ++i) {
    if (cells[i].votes >= 2) order.push_back(static_cast<uint32_t>(i));
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return cells[a].votes != cells[b].votes ? cells[a].votes > cells[b].votes : cells[a].key < cells[b].key;
  });
}

bool RleHough::Impl::groupPeak(uint32_t seed_index, const EdgeObject& object, const HoughOptions& o,
                               const Windows& windows, Peak* peak) {
  // Near-neighbour grouping: the strongest free cell gathers the free cells whose lines are
  // within the window of its own (so +-90 deg and the +45 deg intercept flip are no borders).
  const std::vector<hough::Cell>& cells = accumulator.cells();
  const std::vector<hough::CellLine>& cell_h = accumulator.cellLines();
  const hough::CellLine& hs = cell_h[seed_index];
  // The foot of the object's centroid on the seed line: offsets are measured there.
  const double d0 = distance(hs, object.cx, object.cy);
  const double qx = object.cx - d0 * hs.a, qy = object.cy - d0 * hs.b;
  const int seed_bin = accumulator.thetaBinOf(seed_index);
  const int theta_bins = accumulator.thetaBins();
  uint32_t votes = 0;
  double weighted_offset = 0, weighted_angle = 0;
  members.clear();
  for (int db = -windows.peak_bins; db <= windows.peak_bins; ++db) {
    const int bin = ((seed_bin + db) % theta_bins + theta_bins) % theta_bins;
    for (int i = accumulator.binBegin(bin); i < accumulator.binEnd(bin); ++i) {
      if (used[i]) continue;
      const double cosine = cell_h[i].a * hs.a + cell_h[i].b * hs.b;  // cos of the angle between normals
      if (std::fabs(cosine) < windows.cos_peak) continue;
      const double angle = normalizeLineAngle(cell_h[i].theta - hs.theta);
      // Lines of opposite orientation have opposite normals: measure along the seed's.
      const double offset = distance(cell_h[i], qx, qy);
      const double signed_offset = cosine >= 0 ? offset : -offset;
      if (std::fabs(signed_offset) > o.peak_distance_px) continue;
      members.push_back(i);
      votes += cells[i].votes;
      weighted_offset += cells[i].votes * signed_offset;
      weighted_angle += cells[i].votes * angle;
    }
  }
  if (static_cast<int>(votes) < o.min_votes) return false;
  for (size_t i : members) used[i] = 1;
  // Start from the vote-weighted mean of the group.
  peak->votes = votes;
  peak->start = lineThroughPointWithAngle(qx + weighted_offset / votes * hs.a, qy + weighted_offset / votes * hs.b,
                                          hs.theta + weighted_angle / votes);
  return true;
}

int RleHough::Impl::keepRefined(const ObjectRuns& runs, const Peak& peak, int index, const HoughOptions& o,
                                const Windows& windows, std::vector<DetectedLine>* found) {
  int added = 0;
  for (DetectedLine& line : refined) {
    // The ridge fit follows the edge image, where claims do not hold: a segment may land on
    // one found before (collinear but apart is another segment). Keep the better supported.
    const auto same = std::find_if(found->begin(), found->end(), [&](const DetectedLine& f) {
      return sameSegment(f, line, o.peak_angle_deg * kDeg, o.peak_distance_px);
    });
    line.votes = peak.votes;
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
    const AlongRange range{std::min(ta, tb), std::max(ta, tb)};
    runs.claim(hl, o.fit_distance_px, range);
    retireExplained(line, range, o, windows);
  }
  return added;
}

void RleHough::Impl::retireExplained(const DetectedLine& line, const AlongRange& range, const HoughOptions& o,
                                     const Windows& windows) {
  // Retire the cells the segment explains: pairs drawn along its ridge vote for lines tilted
  // through it, which would otherwise seed it again. They cross it inside; an edge meeting it
  // at a corner crosses at an end, so the ends are left out.
  const std::vector<hough::CellLine>& cell_h = accumulator.cellLines();
  const int theta_bins = accumulator.thetaBins();
  const Homogeneous hl = homogeneous(line.line);
  const double end_margin = std::min(2 * o.fit_distance_px, 0.25 * (range.hi - range.lo));
  const double inside[2] = {range.lo + end_margin, range.hi - end_margin};
  const int line_bin = std::min(theta_bins - 1, std::max(0, static_cast<int>((line.line.theta / kDeg + 90.0) / o.theta_bin_deg)));
  for (int db = windows.first_bin; db <= windows.last_bin; ++db) {
    const int bin = windows.all_bins ? db : ((line_bin + db) % theta_bins + theta_bins) % theta_bins;
    for (int i = accumulator.binBegin(bin); i < accumulator.binEnd(bin); ++i) {
      const hough::CellLine& hc = cell_h[i];
      if (used[i] || std::fabs(hc.a * hl.a + hc.b * hl.b) < windows.cos_explained) continue;
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

bool RleHough::Impl::refine(const ObjectRuns& runs, const ImageLine& seed, const HoughOptions& o,
                            const Refinement& how, std::vector<DetectedLine>* out) {
  // A least-squares fit on the unclaimed pixels near the seed (a coarse cell): a wide band,
  // then the fitting band, which also maps the stretches of pixels along the line.
  ImageLine line = seed;
  PointSums sums;
  double rms = 0;
  // A peak whose pixels lines already found have taken (a second peak of one of them, or
  // chance votes across them) is not worth a refit: counted in the same pass.
  double unclaimed_near = 0;
  const Homogeneous hs = homogeneous(line);
  int near_row = -1, near_lo = 0, near_hi = -1;  // the fitting band's columns in row near_row
  runs.forEachStretch(hs, 2 * o.fit_distance_px, std::nullopt, [&](int y, int x0, int x1, const uint8_t* claimed) {
    if (y != near_row) {  // a row may hold several stretches
      near_row = y;
      runs.bandColumns(hs, o.fit_distance_px, y, &near_lo, &near_hi);
    }
    hough::forEachUnclaimed(x0, x1, claimed, [&](int a, int b) {
      sums.addRun(a, b, y);
      unclaimed_near += std::max(0, std::min(b, near_hi) - std::max(a, near_lo) + 1);
    });
  });
  if (unclaimed_near < 0.5 * o.min_line_length_px) return false;
  if (sums.n < 0.5 * o.min_line_length_px || !sums.fitLine(&line, &rms)) return true;
  sums = PointSums();
  intervals.clear();
  bandIntervals(runs, homogeneous(line), o.fit_distance_px, std::nullopt, &intervals, &sums);
  if (sums.n < 0.5 * o.min_line_length_px || !sums.fitLine(&line, &rms)) return true;

  // No piece can be long enough when all the stretches together span less: skip the sorting.
  double first = INFINITY, last = -INFINITY;
  for (const Interval& i : intervals) {
    first = std::min(first, i.t0);
    last = std::max(last, i.t1);
  }
  if (last - first < o.min_line_length_px) return true;
  // Every stretch long enough gives segments (a horizon broken by obstacles gives several).
  std::vector<DetectedLine> segments;
  for (const Interval& piece : hough::pieces(&intervals, o.max_gap_px)) {
    // Too short, or mostly a line found before (its stretches span corners' claimed pixels).
    if (piece.t1 - piece.t0 < o.min_line_length_px || piece.free_pixels < 0.5 * piece.pixels) continue;
    segments.clear();
    if (!how.edge_image.empty()) {
      ridgeSegments(line, piece, o, how, &segments);
    } else {
      DetectedLine d;
      if (runSegment(runs, line, piece, o, &d)) segments.push_back(d);
    }
    for (DetectedLine& d : segments) {
      const Homogeneous h = homogeneous(d.line);
      const double ta = along(h, d.x1, d.y1), tb = along(h, d.x2, d.y2);
      const PointSums support = unclaimedSums(runs, h, 1.5, AlongRange{std::min(ta, tb) - 0.5, std::max(ta, tb) + 0.5});
      if (d.length < o.min_line_length_px || support.n < o.min_support_ratio * d.length) continue;
      d.support = static_cast<uint32_t>(support.n);
      out->push_back(d);
    }
  }
  return true;
}

void RleHough::Impl::ridgeSegments(const ImageLine& line, const Interval& piece, const HoughOptions& o,
                                   const Refinement& how, std::vector<DetectedLine>* segments) {
  // Sub-pixel: ridge centres along the line, robustly fitted, split where they bend.
  RidgeFitOptions ridge;
  ridge.half_width_px = o.fit_distance_px;
  ridge.min_strength = how.ridge_strength;
  ridge.max_gap_px = o.max_gap_px;
  // Near a corner the ridge bends away: the straight stretch may fall short of the pixels'
  // extent by up to a fitting band at each end, which the segment then gets back.
  const double reach = o.fit_distance_px;
  ridge_fitter.fit(how.edge_image, line, piece.t0 - 2, piece.t1 + 2, ridge, std::max(5.0, o.min_line_length_px - 2 * reach),
                   &fits);
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
    segments->push_back(d);
  }
}

bool RleHough::Impl::runSegment(const ObjectRuns& runs, const ImageLine& line, const Interval& piece,
                                const HoughOptions& o, DetectedLine* d) {
  // Without the edge image: a least-squares fit of the stretch's run pixels.
  const AlongRange range{piece.t0 - 0.5, piece.t1 + 0.5};
  d->sums = unclaimedSums(runs, homogeneous(line), o.fit_distance_px, range);
  if (d->sums.n < 2 || !d->sums.fitLine(&d->line, &d->rms)) return false;
  const Homogeneous h = homogeneous(d->line);
  std::vector<Interval> own;
  PointSums unused;
  bandIntervals(runs, h, o.fit_distance_px, range, &own, &unused);
  const Interval extent = mostPixels(hough::pieces(&own, o.max_gap_px));
  // End points: the foot of the perpendicular from the origin plus t along the direction.
  const double fx = -h.c * h.a, fy = -h.c * h.b;
  d->x1 = fx + extent.t0 * h.b;
  d->y1 = fy - extent.t0 * h.a;
  d->x2 = fx + extent.t1 * h.b;
  d->y2 = fy - extent.t1 * h.a;
  d->length = extent.t1 - extent.t0;
  return true;
}

}  // namespace rle_vision
