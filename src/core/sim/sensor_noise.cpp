#include "rle_vision/sim/sensor_noise.h"

#include <cmath>
#include <algorithm>
#include <stdexcept>

namespace rle_vision {
namespace {

constexpr int kTableSize = 1 << 16;

// SplitMix64: a counter hashed to 64 well-mixed bits, so nearby seeds give unrelated streams.
uint64_t splitMix64(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

std::vector<int16_t> roundedGaussianTable(double sigma) {
  if (!std::isfinite(sigma) || sigma <= 0 || sigma > 1000) {
    throw std::invalid_argument("noise sigma must be in (0, 1000] levels");
  }
  std::vector<int16_t> table(kTableSize);
  const double inv_sigma_sqrt2 = 1.0 / (sigma * std::sqrt(2.0));
  // P(round(X) <= k) = P(X < k + 0.5); entry i holds the smallest k whose probability reaches
  // the middle of the i-th 2^-16 slice. Start below every slice (4.3 sigma is the outermost).
  int k = -static_cast<int>(std::ceil(5 * sigma)) - 1;
  for (int i = 0; i < kTableSize; ++i) {
    const double u = (i + 0.5) / kTableSize;
    while (0.5 * std::erfc(-(k + 0.5) * inv_sigma_sqrt2) < u) ++k;
    table[i] = static_cast<int16_t>(k);
  }
  return table;
}

void addGaussianNoise(double sigma, uint64_t seed, cv::Mat* image) {
  if (image->depth() != CV_8U) throw std::invalid_argument("addGaussianNoise needs an 8-bit image");
  if (sigma == 0 || image->empty()) return;
  addGaussianNoise(roundedGaussianTable(sigma), seed, image);
}

void addGaussianNoise(const std::vector<int16_t>& table, uint64_t seed, cv::Mat* image) {
  if (image->depth() != CV_8U) throw std::invalid_argument("addGaussianNoise needs an 8-bit image");
  if (table.size() != kTableSize) throw std::invalid_argument("addGaussianNoise needs a roundedGaussianTable");
  const int values_per_row = image->cols * image->channels();
  uint64_t state = seed;
  for (int y = 0; y < image->rows; ++y) {
    uint8_t* row = image->ptr<uint8_t>(y);
    for (int x = 0; x < values_per_row; x += 4) {
      uint64_t bits = splitMix64(&state);
      const int end = std::min(x + 4, values_per_row);
      for (int i = x; i < end; ++i, bits >>= 16) {
        const int value = row[i] + table[bits & 0xFFFF];
        row[i] = static_cast<uint8_t>(value < 0 ? 0 : (value > 255 ? 255 : value));
      }
    }
  }
}

}  // namespace rle_vision
