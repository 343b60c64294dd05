#include "landmark/horizon_regions.h"

#include "common/simd_dispatch.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {
namespace horizon {
namespace {

constexpr int kPadded = 16;  // moments padded to 16 floats: whole vector registers
constexpr double kDeg = M_PI / 180;
constexpr double kGlobalAngleStepDeg = 4;  // a split's score peak is several degrees wide
// Hypotheses this close are one line (the horizon criterion's own tolerances).
constexpr double kDistinctAngleDeg = 5;
constexpr double kDistinctDistanceShare = 0.05;

RLE_VISION_HOT
void addRow(const uint8_t* __restrict pixels, int n, uint16_t* __restrict sums) {
  for (int i = 0; i < n; ++i) sums[i] = static_cast<uint16_t>(sums[i] + pixels[i]);
}

// The sums over the cells above v_b = v0 + dv (c + 0.5) in every column c (the cell it falls
// in counting in part): prefix sums `down` ((rows + 1) x cols x kPadded) and the cells' own
// `moments`. Likewise across rows with `right` for steep lines.
RLE_VISION_HOT
void sumAboveInColumns(const float* __restrict down, const float* __restrict moments, int rows, int cols, float v0,
                       float dv, float* __restrict acc) {
  alignas(64) float sum[kPadded] = {0};
  for (int c = 0; c < cols; ++c) {
    const float vb = std::min(std::max(v0 + dv * (c + 0.5f), 0.0f), static_cast<float>(rows));
    const int row = std::min(static_cast<int>(vb), rows - 1);
    const float part = vb - row;
    const float* above = down + (static_cast<size_t>(row) * cols + c) * kPadded;
    const float* m = moments + (static_cast<size_t>(row) * cols + c) * kPadded;
    for (int k = 0; k < kPadded; ++k) sum[k] += above[k] + part * m[k];
  }
  for (int k = 0; k < kPadded; ++k) acc[k] += sum[k];
}

RLE_VISION_HOT
void sumLeftInRows(const float* __restrict right, const float* __restrict moments, int rows, int cols, float u0,
                   float du, float* __restrict acc) {
  alignas(64) float sum[kPadded] = {0};
  for (int row = 0; row < rows; ++row) {
    const float ub = std::min(std::max(u0 + du * (row + 0.5f), 0.0f), static_cast<float>(cols));
    const int c = std::min(static_cast<int>(ub), cols - 1);
    const float part = ub - c;
    const float* left = right + (static_cast<size_t>(row) * (cols + 1) + c) * kPadded;
    const float* m = moments + (static_cast<size_t>(row) * cols + c) * kPadded;
    for (int k = 0; k < kPadded; ++k) sum[k] += left[k] + part * m[k];
  }
  for (int k = 0; k < kPadded; ++k) acc[k] += sum[k];
}

bool sameLine(const Hypothesis& a, const Hypothesis& b, int height) {
  double da = std::fabs(a.angle_deg - b.angle_deg), dd = std::fabs(a.centre_distance - b.centre_distance);
  if (da > 90) {  // across +-90 deg the normal flips
    da = 180 - da;
    dd = std::fabs(a.centre_distance + b.centre_distance);
  }
  return da < kDistinctAngleDeg && dd < kDistinctDistanceShare * height;
}

}  // namespace

SplitLine SplitLine::fromAngleDistance(double angle_deg, double centre_distance, int width, int height) {
  SplitLine l;
  l.angle_deg = angle_deg;
  l.nx = -std::sin(angle_deg * kDeg);
  l.ny = std::cos(angle_deg * kDeg);
  l.rho = l.nx * 0.5 * width + l.ny * 0.5 * height + centre_distance;
  return l;
}

SplitLine SplitLine::fromImageLine(const ImageLine& line) {
  SplitLine l;
  double c;
  homogeneousFromLine(line, &l.nx, &l.ny, &c);  // (nx, ny) = (-sin theta, cos theta), ny >= 0
  l.rho = -c;
  l.angle_deg = line.theta / kDeg;
  return l;
}

double covarianceDet(const double* m) {
  const double det =
      m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
  return std::max(det, kMinCovarianceDet);
}

SideStats sideStats(const double* s, double noise_variance) {
  SideStats st;
  st.n = s[0];
  const double inv = 1.0 / std::max(st.n, 1e-9);
  for (int c = 0; c < 3; ++c) st.mean[c] = s[1 + c] * inv;
  const double* m = st.mean;
  st.cov[0] = s[4] * inv - m[0] * m[0] + noise_variance;
  st.cov[1] = st.cov[3] = s[5] * inv - m[0] * m[1];
  st.cov[2] = st.cov[6] = s[6] * inv - m[0] * m[2];
  st.cov[4] = s[7] * inv - m[1] * m[1] + noise_variance;
  st.cov[5] = st.cov[7] = s[8] * inv - m[1] * m[2];
  st.cov[8] = s[9] * inv - m[2] * m[2] + noise_variance;
  return st;
}

void RegionGrid::build(const cv::Mat& bgr, int cell) {
  CV_Assert(bgr.type() == CV_8UC3 && cell >= 1 && cell <= kMaxCell);
  cell_ = cell;
  rows_ = bgr.rows / cell;
  cols_ = bgr.cols / cell;
  means_.resize(static_cast<size_t>(rows_) * cols_ * 3);
  // Box sums: `cell` rows added into 16-bit column sums (255 x cell fits: cell <= kMaxCell),
  // then `cell` columns per box.
  row_sums_.resize(static_cast<size_t>(bgr.cols) * 3);
  const float inv = 1.0f / static_cast<float>(cell * cell);
  for (int r = 0; r < rows_; ++r) {
    std::fill(row_sums_.begin(), row_sums_.end(), 0);
    for (int y = r * cell; y < (r + 1) * cell; ++y) addRow(bgr.ptr<uint8_t>(y), bgr.cols * 3, row_sums_.data());
    for (int c = 0; c < cols_; ++c) {
      int sum[3] = {0, 0, 0};
      const uint16_t* q = &row_sums_[static_cast<size_t>(c) * cell * 3];
      for (int i = 0; i < cell; ++i) {
        for (int ch = 0; ch < 3; ++ch) sum[ch] += q[3 * i + ch];
      }
      float* out = &means_[(static_cast<size_t>(r) * cols_ + c) * 3];
      for (int ch = 0; ch < 3; ++ch) out[ch] = static_cast<float>(sum[ch]) * inv;
    }
  }
  computeMoments();
}

void RegionGrid::buildHalf(const RegionGrid& finer) {
  cell_ = 2 * finer.cell_;
  rows_ = finer.rows_ / 2;
  cols_ = finer.cols_ / 2;
  means_.resize(static_cast<size_t>(rows_) * cols_ * 3);
  for (int r = 0; r < rows_; ++r) {
    for (int c = 0; c < cols_; ++c) {
      for (int ch = 0; ch < 3; ++ch) {
        means_[(static_cast<size_t>(r) * cols_ + c) * 3 + ch] =
            0.25f * (finer.colour(2 * r, 2 * c)[ch] + finer.colour(2 * r, 2 * c + 1)[ch] +
                     finer.colour(2 * r + 1, 2 * c)[ch] + finer.colour(2 * r + 1, 2 * c + 1)[ch]);
      }
    }
  }
  computeMoments();
}

void RegionGrid::computeMoments() {
  const size_t cells = static_cast<size_t>(rows_) * cols_;
  luma_.resize(cells);
  for (size_t i = 0; i < cells; ++i) {
    const float* bgr = &means_[i * 3];
    luma_[i] = static_cast<uint8_t>(std::min(255.0f, 0.114f * bgr[0] + 0.587f * bgr[1] + 0.299f * bgr[2] + 0.5f));
  }
  // Colours centred on the frame's mean keep the float sums of squares accurate.
  double mean[3] = {0, 0, 0};
  for (size_t i = 0; i < cells; ++i) {
    for (int ch = 0; ch < 3; ++ch) mean[ch] += means_[i * 3 + ch];
  }
  for (double& m : mean) m /= std::max<size_t>(cells, 1);
  // Every entry is written below: no zero fill first.
  moments_.resize(cells * kPadded);
  for (size_t i = 0; i < cells; ++i) {
    const float c0 = static_cast<float>(means_[i * 3] - mean[0]);
    const float c1 = static_cast<float>(means_[i * 3 + 1] - mean[1]);
    const float c2 = static_cast<float>(means_[i * 3 + 2] - mean[2]);
    float* m = &moments_[i * kPadded];
    m[0] = 1;
    m[1] = c0;
    m[2] = c1;
    m[3] = c2;
    m[4] = c0 * c0;
    m[5] = c0 * c1;
    m[6] = c0 * c2;
    m[7] = c1 * c1;
    m[8] = c1 * c2;
    m[9] = c2 * c2;
    std::fill(m + kMoments, m + kPadded, 0.0f);
  }
  down_.resize(static_cast<size_t>(rows_ + 1) * cols_ * kPadded);
  std::fill(down_.begin(), down_.begin() + static_cast<size_t>(cols_) * kPadded, 0.0f);  // nothing above row 0
  for (int r = 0; r < rows_; ++r) {
    for (size_t k = 0; k < static_cast<size_t>(cols_) * kPadded; ++k) {
      down_[(static_cast<size_t>(r) + 1) * cols_ * kPadded + k] =
          down_[static_cast<size_t>(r) * cols_ * kPadded + k] + moments_[static_cast<size_t>(r) * cols_ * kPadded + k];
    }
  }
  right_.resize(static_cast<size_t>(rows_) * (cols_ + 1) * kPadded);
  for (int r = 0; r < rows_; ++r) {
    float* first = &right_[static_cast<size_t>(r) * (cols_ + 1) * kPadded];
    std::fill(first, first + kPadded, 0.0f);  // nothing left of column 0
    for (int c = 0; c < cols_; ++c) {
      const float* left = &right_[(static_cast<size_t>(r) * (cols_ + 1) + c) * kPadded];
      const float* m = &moments_[(static_cast<size_t>(r) * cols_ + c) * kPadded];
      float* out = &right_[(static_cast<size_t>(r) * (cols_ + 1) + c + 1) * kPadded];
      for (int k = 0; k < kPadded; ++k) out[k] = left[k] + m[k];
    }
  }
  for (int k = 0; k < kMoments; ++k) {
    double t = 0;
    for (int c = 0; c < cols_; ++c) t += down_[(static_cast<size_t>(rows_) * cols_ + c) * kPadded + k];
    total_[k] = t;
  }
}

void RegionGrid::skySideSums(const SplitLine& line, double* sums) const {
  // Full-resolution pixel centres x map to grid coordinates u = (x + 0.5) / cell.
  const double r = (line.rho + 0.5 * (line.nx + line.ny)) / cell_;
  alignas(64) float acc[kPadded] = {0};
  const bool flat = std::fabs(line.ny) >= std::fabs(line.nx);
  if (flat) {  // per column: the cells above v_b
    sumAboveInColumns(down_.data(), moments_.data(), rows_, cols_, static_cast<float>(r / line.ny),
                      static_cast<float>(-line.nx / line.ny), acc);
  } else {  // per row: the cells left of u_b
    sumLeftInRows(right_.data(), moments_.data(), rows_, cols_, static_cast<float>(r / line.nx),
                  static_cast<float>(-line.ny / line.nx), acc);
  }
  for (int k = 0; k < kMoments; ++k) sums[k] = acc[k];
  if (!flat && line.nx < 0) {  // the sky side is then right of u_b
    for (int k = 0; k < kMoments; ++k) sums[k] = total_[k] - sums[k];
  }
}

namespace {

// A split's score: the two-Gaussian log-likelihood gain of splitting the grid along a line
// (larger: a better split), or -infinity when a side holds less than `min_fraction` of the
// frame. The whole frame's covariance, the same for every line of a search, is measured once.
class SplitScorer {
 public:
  SplitScorer(const RegionGrid& grid, double noise_variance, double min_fraction)
      : grid_(grid),
        noise_variance_(noise_variance),
        min_fraction_(min_fraction),
        log_det_total_(std::log(covarianceDet(sideStats(grid.total(), noise_variance).cov))) {}

  double operator()(const SplitLine& line) const {
    double sky[kMoments], ground[kMoments];
    grid_.skySideSums(line, sky);
    const double* total = grid_.total();
    const double fraction = sky[0] / total[0];
    if (!(fraction >= min_fraction_ && fraction <= 1 - min_fraction_)) return -INFINITY;
    for (int k = 0; k < kMoments; ++k) ground[k] = total[k] - sky[k];
    const SideStats a = sideStats(sky, noise_variance_), b = sideStats(ground, noise_variance_);
    return log_det_total_ -
           (a.n * std::log(covarianceDet(a.cov)) + b.n * std::log(covarianceDet(b.cov))) / (a.n + b.n);
  }

 private:
  const RegionGrid& grid_;
  double noise_variance_, min_fraction_, log_det_total_;
};

// The line at `angle_deg` through the frame's centre: the lines of one angle differ only in
// rho, by their centre distance (the sine and cosine taken once per angle).
SplitLine centreLine(double angle_deg, int width, int height) {
  return SplitLine::fromAngleDistance(angle_deg, 0, width, height);
}

SplitLine shifted(SplitLine line, double centre_distance) {
  line.rho += centre_distance;
  return line;
}

}  // namespace

std::vector<Hypothesis> searchSplits(const RegionGrid& fine, const RegionGrid& coarse, int width, int height,
                                     const SearchOptions& o) {
  std::vector<Hypothesis> all;
  const double reach = 0.5 * std::hypot(width, height), step = coarse.cell();
  const SplitScorer coarse_score(coarse, o.noise_variance, o.min_fraction);
  const SplitScorer fine_score(fine, o.noise_variance, o.min_fraction);
  for (double a = -90 + kGlobalAngleStepDeg; a <= 90 + 1e-9; a += kGlobalAngleStepDeg) {
    if (std::fabs(a) > o.max_angle_deg) continue;
    const SplitLine centre = centreLine(a, width, height);
    // Lines that cross the image.
    const double extent = 0.5 * (width * std::fabs(centre.nx) + height * std::fabs(centre.ny));
    for (double d = -reach; d <= reach + 1e-9; d += step) {
      if (std::fabs(d) > extent) continue;
      const double score = coarse_score(shifted(centre, d));
      if (std::isfinite(score)) all.push_back({a, d, score});
    }
  }
  std::sort(all.begin(), all.end(), [](const Hypothesis& x, const Hypothesis& y) { return x.score > y.score; });
  std::vector<Hypothesis> best;
  for (const Hypothesis& h : all) {
    if (static_cast<int>(best.size()) >= o.hypotheses) break;
    if (std::none_of(best.begin(), best.end(), [&](const Hypothesis& b) { return sameLine(h, b, height); })) best.push_back(h);
  }
  // Each refined on the fine grid: quarter steps around it (the global grid alone misranks
  // near ties).
  for (Hypothesis& h : best) {
    Hypothesis refined{h.angle_deg, h.centre_distance, -INFINITY};
    for (int i = -4; i <= 4; ++i) {
      double a = h.angle_deg + i * kGlobalAngleStepDeg / 4;
      const bool flipped = a > 90 || a <= -90;  // the same line with its normal flipped
      if (flipped) a += a > 90 ? -180 : 180;
      if (std::fabs(a) > o.max_angle_deg) continue;
      const SplitLine centre = centreLine(a, width, height);
      for (int j = -4; j <= 4; ++j) {
        const double d = (flipped ? -1 : 1) * (h.centre_distance + j * step / 4);
        const double score = fine_score(shifted(centre, d));
        if (score > refined.score) refined = {a, d, score};
      }
    }
    h = refined;
  }
  std::sort(best.begin(), best.end(), [](const Hypothesis& x, const Hypothesis& y) { return x.score > y.score; });
  return best;
}

}  // namespace horizon
}  // namespace rle_vision
