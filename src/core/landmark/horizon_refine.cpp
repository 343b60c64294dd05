#include "landmark/horizon_refine.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {
namespace horizon {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kAngleStepDeg = 0.25;  // the robust fit's angle steps
constexpr int kSampleStride = 4;        // every 4th row and column samples the sides' edge values

// P(a > b) + P(a == b) / 2 from two histograms of 256 bins (normalised or not).
template <typename Count>
double probabilityGreater(const Count* a, double a_total, const Count* b, double b_total) {
  if (a_total <= 0 || b_total <= 0) return 0.5;
  double below = 0, p = 0;
  for (int v = 0; v < 256; ++v) {
    p += a[v] * (below + 0.5 * static_cast<double>(b[v]));
    below += b[v];
  }
  return p / (a_total * b_total);
}

// An edge value over the brightness around it, (edge + 1) / (luma + kDarkLuma), as one of 256
// bins on a log scale (monotonic: comparisons between bins are comparisons of the ratios).
// kDarkLuma keeps the darkest cells, where the sensor's noise is the texture, from dividing by
// nothing.
constexpr double kDarkLuma = 16;
constexpr uint8_t kMidGrey = 128;
struct RelativeContrastBins {
  uint8_t bin[256][256];  // [luma][edge]
  RelativeContrastBins() {
    for (int luma = 0; luma < 256; ++luma) {
      for (int edge = 0; edge < 256; ++edge) {
        const double b = 170 + 20 * std::log2((edge + 1.0) / (luma + kDarkLuma));
        bin[luma][edge] = static_cast<uint8_t>(std::clamp(static_cast<int>(b), 0, 255));
      }
    }
  }
};
int relativeContrastBin(uint8_t edge, uint8_t luma) {
  static const RelativeContrastBins table;
  return table.bin[luma][edge];
}

// The texture samples (every kSampleStride-th column) at pixel columns first..last of a row.
template <class Visit>
void forEachSample(int first, int last, Visit&& visit) {
  for (int i = (first + kSampleStride - 1) / kSampleStride; i * kSampleStride <= last; ++i) visit(i);
}

// The value below which `percentile` % of a histogram's samples lie.
double percentileOf(const int* histogram, int total, double percentile) {
  if (total == 0) return 0;
  const int target = static_cast<int>(std::ceil(percentile / 100.0 * total));
  int seen = 0;
  for (int v = 0; v < 256; ++v) {
    seen += histogram[v];
    if (seen >= target) return v;
  }
  return 255;
}

// Calls visit(first, last, sky) for the samples of row y at x = first, first + stride, ...,
// last that lie farther than `band` from the line on its sky side (sky = true) or ground side.
template <class Visit>
void sideRanges(const SplitLine& line, double y, int width, double band, Visit&& visit) {
  // d(x) = nx x + ny y - rho; the sky side is d < -band, the ground side d > band.
  const double base = line.ny * y - line.rho;
  if (std::fabs(line.nx) < 1e-12) {
    if (base < -band) visit(0, width - 1, true);
    if (base > band) visit(0, width - 1, false);
    return;
  }
  // x where d = -band and d = +band (clamped to just outside the row before converting); the
  // sky lies on the side where d decreases.
  auto clampX = [width](double x) { return std::min(std::max(x, -1.0), static_cast<double>(width)); };
  const double x_sky = clampX((-band - base) / line.nx), x_ground = clampX((band - base) / line.nx);
  if (line.nx > 0) {  // d grows with x: sky at small x
    visit(0, std::min(width - 1, static_cast<int>(std::ceil(x_sky)) - 1), true);
    visit(std::max(0, static_cast<int>(std::floor(x_ground)) + 1), width - 1, false);
  } else {
    visit(std::max(0, static_cast<int>(std::floor(x_sky)) + 1), width - 1, true);
    visit(0, std::min(width - 1, static_cast<int>(std::ceil(x_ground)) - 1), false);
  }
}

double bhattacharyyaDistance(const SideStats& a, const SideStats& b) {
  double c[9], d[3];
  for (int k = 0; k < 9; ++k) c[k] = 0.5 * (a.cov[k] + b.cov[k]);
  for (int k = 0; k < 3; ++k) d[k] = a.mean[k] - b.mean[k];
  const double det = covarianceDet(c);
  // d^T c^-1 d through the adjugate.
  const double adj[9] = {c[4] * c[8] - c[5] * c[7], c[2] * c[7] - c[1] * c[8], c[1] * c[5] - c[2] * c[4],
                         c[5] * c[6] - c[3] * c[8], c[0] * c[8] - c[2] * c[6], c[2] * c[3] - c[0] * c[5],
                         c[3] * c[7] - c[4] * c[6], c[1] * c[6] - c[0] * c[7], c[0] * c[4] - c[1] * c[3]};
  double quad = 0;
  for (int i = 0; i < 3; ++i) {
    double row = 0;
    for (int j = 0; j < 3; ++j) row += adj[i * 3 + j] * d[j];
    quad += d[i] * row;
  }
  return 0.125 * quad / det + 0.5 * std::log(det / std::sqrt(covarianceDet(a.cov) * covarianceDet(b.cov)));
}

}  // namespace

void HorizonRefiner::measureBand(const cv::Mat& edges, const SplitLine& line, double band) {
  // The sky's own edge values (away from the band): a horizon point must beat most of them.
  std::fill(std::begin(sky_histogram_), std::end(sky_histogram_), 0);
  sky_samples_ = 0;
  for (int r = 0; r < sampled_edges_.rows; ++r) {
    const uint8_t* e = sampled_edges_.ptr<uint8_t>(r);
    sideRanges(line, r * kSampleStride, edges.cols, band, [&](int first, int last, bool sky) {
      if (!sky) return;
      forEachSample(first, last, [&](int i) {
        ++sky_histogram_[e[i]];
        ++sky_samples_;
      });
    });
  }
  // The scanlines across the band (columns, rows for steep lines), and the typical maximum.
  const bool flat = std::fabs(line.ny) >= std::fabs(line.nx);
  const int count = flat ? edges.cols : edges.rows, length = flat ? edges.rows : edges.cols;
  const double along = flat ? line.ny : line.nx, across = flat ? line.nx : line.ny;
  scans_.assign(count, Scan{0, -1});
  maxima_.clear();
  for (int f = 0; f < count; ++f) {
    const double centre = (line.rho - across * f) / along;
    const int lo = std::max(static_cast<int>(std::floor(centre - band)), 1);
    const int hi = std::min(static_cast<int>(std::ceil(centre + band)), length - 2);
    if (hi - lo < 2) continue;
    scans_[f] = {lo, hi};
    int peak = 0;
    for (int k = lo; k <= hi; ++k) peak = std::max<int>(peak, flat ? edges.ptr<uint8_t>(k)[f] : edges.ptr<uint8_t>(f)[k]);
    maxima_.push_back(peak);
  }
  typical_peak_ = -1;
  if (!maxima_.empty()) {
    std::nth_element(maxima_.begin(), maxima_.begin() + maxima_.size() / 2, maxima_.end());
    typical_peak_ = maxima_[maxima_.size() / 2];
  }
}

double HorizonRefiner::threshold(double sky_percentile, const RefineOptions& o) {
  sky_edge_level_ = percentileOf(sky_histogram_, sky_samples_, sky_percentile);
  double t = std::max(sky_edge_level_, o.edge_floor);
  if (typical_peak_ >= 0) t = std::max(t, o.peak_ratio * typical_peak_);
  return t;
}

void HorizonRefiner::scanPoints(const cv::Mat& edges, const SplitLine& line, double threshold) {
  const bool flat = std::fabs(line.ny) >= std::fabs(line.nx);
  const bool from_low_end = (flat ? line.ny : line.nx) > 0;  // the sky side is at the low coordinates
  px_.clear();
  py_.clear();
  for (int f = 0; f < static_cast<int>(scans_.size()); ++f) {
    const Scan& s = scans_[f];
    if (s.hi < s.lo) continue;
    auto at = [&](int k) -> int { return flat ? edges.ptr<uint8_t>(k)[f] : edges.ptr<uint8_t>(f)[k]; };
    for (int step = 0; step <= s.hi - s.lo; ++step) {
      const int k = from_low_end ? s.lo + step : s.hi - step;
      const int c = at(k), l = at(k - 1), r = at(k + 1);
      if (c < threshold || c < l || c < r || (l == c && r == c)) continue;
      const double curvature = l - 2.0 * c + r;
      const double position = k + (curvature < 0 ? 0.5 * (l - r) / curvature : 0.0);  // parabola vertex
      px_.push_back(flat ? f : position);
      py_.push_back(flat ? position : f);
      break;
    }
  }
}

bool HorizonRefiner::robustFit(const SplitLine& start, const RefineOptions& o, SplitLine* fitted) {
  const size_t n = px_.size();
  // A local Hough: for angles around the hypothesis, the 1-px offset bin whose window of
  // +-inlier_px holds the most points.
  const int window = static_cast<int>(std::lround(o.inlier_px));
  const int angle_steps = static_cast<int>(std::lround(o.angle_range_deg / kAngleStepDeg));
  int best_votes = -1;
  double best_angle = start.angle_deg, best_rho = start.rho;
  offsets_.resize(n);
  for (int k = -angle_steps; k <= angle_steps; ++k) {
    const double a = (start.angle_deg + k * kAngleStepDeg) * kDeg, nx = -std::sin(a), ny = std::cos(a);
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; ++i) {
      offsets_[i] = px_[i] * nx + py_[i] * ny;
      lo = std::min(lo, offsets_[i]);
      hi = std::max(hi, offsets_[i]);
    }
    lo = std::floor(lo);
    histogram_.assign(static_cast<size_t>(hi - lo) + 2, 0);
    for (size_t i = 0; i < n; ++i) ++histogram_[static_cast<size_t>(offsets_[i] - lo)];
    const int bins = static_cast<int>(histogram_.size());
    int votes = 0;
    for (int b = 0; b < std::min(window, bins); ++b) votes += histogram_[b];
    for (int j = 0; j < bins; ++j) {  // the window [j - window, j + window]
      if (j + window < bins) votes += histogram_[j + window];
      if (j - window - 1 >= 0) votes -= histogram_[j - window - 1];
      if (votes > best_votes) {
        best_votes = votes;
        best_angle = start.angle_deg + k * kAngleStepDeg;
        best_rho = lo + j + 0.5;
      }
    }
  }
  // Total least squares on its points, then twice more with Tukey weights.
  double nx = -std::sin(best_angle * kDeg), ny = std::cos(best_angle * kDeg), rho = best_rho;
  weights_.resize(n);
  for (size_t i = 0; i < n; ++i) weights_[i] = std::fabs(px_[i] * nx + py_[i] * ny - rho) <= o.inlier_px + 0.5 ? 1.0 : 0.0;
  for (int iteration = 0; iteration < 3; ++iteration) {
    double w = 0, cx = 0, cy = 0;
    for (size_t i = 0; i < n; ++i) {
      w += weights_[i];
      cx += weights_[i] * px_[i];
      cy += weights_[i] * py_[i];
    }
    if (w < 3) return false;
    cx /= w;
    cy /= w;
    double sxx = 0, sxy = 0, syy = 0;
    for (size_t i = 0; i < n; ++i) {
      const double dx = px_[i] - cx, dy = py_[i] - cy;
      sxx += weights_[i] * dx * dx;
      sxy += weights_[i] * dx * dy;
      syy += weights_[i] * dy * dy;
    }
    const double direction = 0.5 * std::atan2(2 * sxy, sxx - syy);  // of the largest spread
    nx = -std::sin(direction);
    ny = std::cos(direction);
    if (ny < 0 || (ny == 0 && nx > 0)) {
      nx = -nx;
      ny = -ny;
    }
    rho = nx * cx + ny * cy;
    for (size_t i = 0; i < n; ++i) {
      const double u = std::min(std::fabs(px_[i] * nx + py_[i] * ny - rho) / (2 * o.inlier_px), 1.0);
      weights_[i] = (1 - u * u) * (1 - u * u);
    }
  }
  fitted->nx = nx;
  fitted->ny = ny;
  fitted->rho = rho;
  fitted->angle_deg = std::atan2(-nx, ny) / kDeg;
  return true;
}

void HorizonRefiner::sampleTexture(const cv::Mat& edges, const RegionGrid& fine) {
  const int rows = (edges.rows + kSampleStride - 1) / kSampleStride, cols = (edges.cols + kSampleStride - 1) / kSampleStride;
  sampled_edges_.create(rows, cols, CV_8UC1);
  sampled_relative_.create(rows, cols, CV_8UC1);
  const int s = fine.cell(), last_row = fine.rows() - 1, last_col = fine.cols() - 1;
  for (int r = 0; r < rows; ++r) {
    const uint8_t* row = edges.ptr<uint8_t>(r * kSampleStride);
    const uint8_t* luma = fine.luma(std::min(r * kSampleStride / s, last_row));
    uint8_t* edge = sampled_edges_.ptr<uint8_t>(r);
    uint8_t* relative = sampled_relative_.ptr<uint8_t>(r);
    for (int i = 0; i < cols; ++i) {
      const int x = i * kSampleStride;
      edge[i] = row[x];
      relative[i] = relativeContrastBin(row[x], luma[std::min(x / s, last_col)]);
    }
  }
}

void HorizonRefiner::checkSamples(const cv::Mat& edges) const {
  // The samples are the frame's own: sampleTexture(edges, ...) first, for this edge image.
  CV_Assert(sampled_edges_.rows == (edges.rows + kSampleStride - 1) / kSampleStride &&
            sampled_edges_.cols == (edges.cols + kSampleStride - 1) / kSampleStride);
}

namespace {
// Two lines within the fit's resolution (two angle steps, an inlier distance) of each other.
bool sameLine(const SplitLine& a, const SplitLine& b, double inlier_px) {
  return std::fabs(a.angle_deg - b.angle_deg) < 2 * kAngleStepDeg && std::fabs(a.rho - b.rho) < inlier_px;
}
}  // namespace

RefinedHorizon HorizonRefiner::refine(const cv::Mat& edges, const RegionGrid& fine, const Hypothesis& h,
                                      const RefineOptions& o) {
  RefinedHorizon out;
  refineEach(edges, fine, h, o, {o.sky_percentile}, [&](const RefinedHorizon& r) {
    out = r;
    return true;
  });
  return out;
}

void HorizonRefiner::refineEach(const cv::Mat& edges, const RegionGrid& fine, const Hypothesis& h, const RefineOptions& o,
                                const std::vector<double>& sky_percentiles, const RefinedSink& take) {
  checkSamples(edges);
  const SplitLine start = SplitLine::fromAngleDistance(h.angle_deg, h.centre_distance, edges.cols, edges.rows);
  measureBand(edges, start, o.band_cells * fine.cell());
  refined_lines_.clear();
  double previous_threshold = -1;
  for (const double percentile : sky_percentiles) {
    const double t = threshold(percentile, o);
    if (t == previous_threshold) continue;  // the same points: the same line
    previous_threshold = t;
    RefinedHorizon r = fitAt(edges, start, t, o);
    // A lower threshold that found a line already refined adds nothing.
    const auto same = [&](const SplitLine& k) { return sameLine(k, r.line, o.inlier_px); };
    if (std::any_of(refined_lines_.begin(), refined_lines_.end(), same)) continue;
    refined_lines_.push_back(r.line);
    r.edge_at_line = medianEdgeAtInliers(edges, r.line, o.inlier_px);
    r.evidence = evidence(edges, fine, r.line, o);
    r.evidence.local_step = localStep(fine, r.line, std::sqrt(o.noise_variance));
    if (take(r)) return;
  }
}

RefinedHorizon HorizonRefiner::fitAt(const cv::Mat& edges, const SplitLine& start, double threshold, const RefineOptions& o) {
  RefinedHorizon out;
  out.line = start;
  scanPoints(edges, out.line, threshold);
  out.points = static_cast<int>(px_.size());
  out.scanlines = static_cast<int>(std::count_if(scans_.begin(), scans_.end(), [](const Scan& s) { return s.hi >= s.lo; }));
  SplitLine fitted;
  if (out.points >= o.min_points && robustFit(out.line, o, &fitted)) out.line = fitted;
  out.t_min = INFINITY;
  out.t_max = -INFINITY;
  double squares = 0;
  for (size_t i = 0; i < px_.size(); ++i) {
    const double d = out.line.signedDistance(px_[i], py_[i]);
    if (std::fabs(d) > o.inlier_px) continue;
    ++out.inliers;
    squares += d * d;
    const double t = px_[i] * out.line.ny - py_[i] * out.line.nx;  // along the direction (cos a, sin a)
    out.t_min = std::min(out.t_min, t);
    out.t_max = std::max(out.t_max, t);
  }
  out.rms = out.inliers > 0 ? std::sqrt(squares / out.inliers) : 0;
  out.sky_edge_level = std::max(sky_edge_level_, o.edge_floor);
  return out;
}

double HorizonRefiner::medianEdgeAtInliers(const cv::Mat& edges, const SplitLine& line, double inlier_px) {
  steps_.clear();
  for (size_t i = 0; i < px_.size(); ++i) {
    if (std::fabs(line.signedDistance(px_[i], py_[i])) > inlier_px) continue;
    const int x = std::clamp(static_cast<int>(std::lround(px_[i])), 0, edges.cols - 1);
    const int y = std::clamp(static_cast<int>(std::lround(py_[i])), 0, edges.rows - 1);
    steps_.push_back(edges.ptr<uint8_t>(y)[x]);
  }
  if (steps_.empty()) return 0;
  std::nth_element(steps_.begin(), steps_.begin() + steps_.size() / 2, steps_.end());
  return steps_[steps_.size() / 2];
}

double HorizonRefiner::localStep(const RegionGrid& fine, const SplitLine& line, double noise) {
  // Along the line in cell units: per cell column (row for steep lines), the cells 1.5 and 3.5
  // cells from the line on each side (nearest cells).
  const int s = fine.cell();
  const bool flat = std::fabs(line.ny) >= std::fabs(line.nx);
  const int count = flat ? fine.cols() : fine.rows(), length = flat ? fine.rows() : fine.cols();
  const double along = flat ? line.ny : line.nx, across = flat ? line.nx : line.ny;
  const double sky_direction = along > 0 ? -1 : 1;  // moving this way along the scan goes skywards
  auto distance = [](const float* a, const float* b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  };
  steps_.clear();
  spreads_.clear();
  for (int f = 0; f < count; ++f) {
    const double centre_px = (line.rho - across * (f * s + 0.5 * (s - 1))) / along;  // where the line crosses
    const double centre = (centre_px - 0.5 * (s - 1)) / s;                             // in cells
    int at[4];
    const double offsets[4] = {3.5, 1.5, -1.5, -3.5};  // sky far, sky near, ground near, ground far
    bool inside = true;
    for (int k = 0; k < 4; ++k) {
      at[k] = static_cast<int>(std::lround(centre + sky_direction * offsets[k] / std::fabs(along)));
      inside = inside && at[k] >= 0 && at[k] < length;
    }
    if (!inside) continue;
    auto colour = [&](int k) { return flat ? fine.colour(at[k], f) : fine.colour(f, at[k]); };
    steps_.push_back(distance(colour(1), colour(2)));
    spreads_.push_back(distance(colour(0), colour(1)));
    spreads_.push_back(distance(colour(2), colour(3)));
  }
  if (steps_.empty()) return 0;
  std::nth_element(steps_.begin(), steps_.begin() + steps_.size() / 2, steps_.end());
  std::nth_element(spreads_.begin(), spreads_.begin() + spreads_.size() / 2, spreads_.end());
  return steps_[steps_.size() / 2] / (spreads_[spreads_.size() / 2] + noise);
}

Evidence HorizonRefiner::evidence(const cv::Mat& edges, const RegionGrid& fine, const SplitLine& line,
                                  const RefineOptions& o) {
  checkSamples(edges);
  Evidence e;
  double sky_sums[kMoments], ground_sums[kMoments];
  fine.skySideSums(line, sky_sums);
  for (int k = 0; k < kMoments; ++k) ground_sums[k] = fine.total()[k] - sky_sums[k];
  const SideStats sky = sideStats(sky_sums, o.noise_variance), ground = sideStats(ground_sums, o.noise_variance);
  e.sky_share = sky.n / std::max(fine.total()[0], 1e-9);
  if (std::min(sky.n, ground.n) < 4) return e;
  e.separation = 1 - std::exp(-bhattacharyyaDistance(sky, ground));
  // Brightness: the cells clear of the line (their centres farther than a cell from it).
  const int s = fine.cell();
  double sky_luma[256] = {0}, ground_luma[256] = {0}, sky_cells = 0, ground_cells = 0;
  // In cell coordinates the line is nx (c s + (s-1)/2) + ny (r s + (s-1)/2) = rho.
  SplitLine cells = line;
  cells.rho = (line.rho - 0.5 * (s - 1) * (line.nx + line.ny)) / s;
  for (int r = 0; r < fine.rows(); ++r) {
    const uint8_t* luma = fine.luma(r);
    sideRanges(cells, r, fine.cols(), 1.0, [&](int first, int last, bool sky) {
      for (int c = first; c <= last; ++c) ++(sky ? sky_luma : ground_luma)[luma[c]];
      (sky ? sky_cells : ground_cells) += std::max(0, last - first + 1);
    });
  }
  e.sky_brighter = probabilityGreater(sky_luma, sky_cells, ground_luma, ground_cells);
  // Texture: the frame's samples (sampleTexture) away from the band. Which side is rougher is
  // judged on the contrast relative to the brightness around (Weber), so that a tone curve
  // (gamma, exposure) that squeezes a dark ground's steps and stretches a bright sky's does not
  // swap the sides.
  const double band = o.band_cells * s;
  const int floor_edge = static_cast<int>(std::clamp(std::ceil(o.edge_floor), 0.0, 255.0));
  int sky_relative[256] = {0}, ground_relative[256] = {0}, sky_samples = 0, ground_samples = 0;
  int textured = 0;  // ground samples above the edge value of a noise-level step
  for (int r = 0; r < sampled_edges_.rows; ++r) {
    const uint8_t* edge = sampled_edges_.ptr<uint8_t>(r);
    const uint8_t* relative = sampled_relative_.ptr<uint8_t>(r);
    sideRanges(line, r * kSampleStride, edges.cols, band, [&](int first, int last, bool sky) {
      int* histogram = sky ? sky_relative : ground_relative;
      int samples = 0, above = 0;
      forEachSample(first, last, [&](int i) {
        ++histogram[relative[i]];
        above += edge[i] >= floor_edge;
        ++samples;
      });
      (sky ? sky_samples : ground_samples) += samples;
      if (!sky) textured += above;
    });
  }
  // And in relative terms: above that step on a mid-grey surface (a dark ground's texture,
  // squeezed by the tone curve, still counts).
  int textured_relative = 0;
  for (int v = relativeContrastBin(static_cast<uint8_t>(floor_edge), kMidGrey); v < 256; ++v) {
    textured_relative += ground_relative[v];
  }
  e.ground_textured_relative = ground_samples > 0 ? static_cast<double>(textured_relative) / ground_samples : 0;
  e.ground_rougher = probabilityGreater(ground_relative, ground_samples, sky_relative, sky_samples);
  e.ground_textured = ground_samples > 0 ? static_cast<double>(textured) / ground_samples : 0;
  return e;
}

}  // namespace horizon
}  // namespace rle_vision
