#include "landmark/hough_accumulator.h"

#include <algorithm>
#include <cmath>

#include "landmark/hough_band.h"

namespace rle_vision {
namespace hough {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr uint32_t kEmpty = 0xFFFFFFFFu;

// splitmix64
inline uint64_t random64(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

void Accumulator::vote(const Run* runs, int run_count, uint64_t samples, uint64_t seed, int width, int height,
                       const HoughOptions& o) {
  fillPixelTable(runs, run_count);
  sizeAccumulator(samples, width, height, o);
  drawPairs(samples, seed, o);
  countVotes();
  computeCellLines(o);
}

void Accumulator::fillPixelTable(const Run* runs, int run_count) {
  // Uniform over the runs' pixels, which is the paper's "a run weighted by its length, then a
  // position in it": drawn from a flat table of the pixels.
  size_t total = 0;
  for (int i = 0; i < run_count; ++i) total += runs[i].length();
  pixels_.resize(total);
  PixelXY* pixel = pixels_.data();
  for (int i = 0; i < run_count; ++i) {
    for (int x = runs[i].x0; x <= runs[i].x1; ++x) *pixel++ = {static_cast<int16_t>(x), static_cast<int16_t>(runs[i].y)};
  }
}

void Accumulator::sizeAccumulator(uint64_t samples, int width, int height, const HoughOptions& o) {
  // Sparse accumulator: an open-addressing table of (cell key, votes), of which the first
  // `capacity` slots are used; it is kept empty between rounds by clearing the slots used.
  capacity_ = 64;
  while (capacity_ < 2 * samples) capacity_ *= 2;
  if (table_.size() < capacity_) table_.assign(capacity_, Cell{kEmpty, 0});
  occupied_.clear();
  theta_bins_ = static_cast<int>(std::ceil(180.0 / o.theta_bin_deg));
  alpha_ = -std::max(width, height);
  intercept_bins_ = static_cast<int>(std::ceil((width + height - alpha_) / o.intercept_bin_px)) + 1;
}

void Accumulator::drawPairs(uint64_t samples, uint64_t seed, const HoughOptions& o) {
  const size_t total = pixels_.size();
  uint64_t state = seed;
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
    const PixelXY p1 = pick(random64(&state));
    PixelXY p2 = pick(random64(&state));
    int dx = p2.x - p1.x, dy = p2.y - p1.y;
    for (int attempt = 1; attempt < 3 && dx * dx + dy * dy < min_d2; ++attempt) {
      p2 = pick(random64(&state));
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
}

void Accumulator::countVotes() {
  // The votes (apart from the draws, whose divisions overlap when nothing waits on the table).
  for (const uint32_t key : keys_) {
    size_t slot = (key * 2654435761u) & (capacity_ - 1);
    while (table_[slot].key != kEmpty && table_[slot].key != key) slot = (slot + 1) & (capacity_ - 1);
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

void Accumulator::computeCellLines(const HoughOptions& o) {
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
  cell_lines_.resize(cells_.size());
  for (size_t i = 0; i < cells_.size(); ++i) {
    const int tb = static_cast<int>(cells_[i].key / intercept_bins_), cb = static_cast<int>(cells_[i].key % intercept_bins_);
    CellLine& cell = cell_lines_[i];
    cell.theta = bin_theta_[tb];
    const double intercept = alpha_ + (cb + 0.5) * o.intercept_bin_px;
    // c from the intercept point: (0, intercept) or (intercept, 0).
    cell.a = bin_normal_x_[tb];
    cell.b = bin_normal_y_[tb];
    cell.c = usesYIntercept(cell.theta) ? -cell.b * intercept : -cell.a * intercept;
  }
}

}  // namespace hough
}  // namespace rle_vision
