// Simulated sensor noise: zero-mean Gaussian noise on every channel of an 8-bit image, rounded
// to whole levels and saturated, as a camera's read noise shows up in its 8-bit output.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace rle_vision {

// round(N(0, sigma)) by inverse CDF: 2^16 equally likely entries, indexed by a 16-bit uniform
// number. Exact up to the 2^-16 step of the index (tails beyond about 4.3 sigma are cut).
std::vector<int16_t> roundedGaussianTable(double sigma);

// Adds noise of standard deviation sigma (8-bit levels) to every channel of an 8-bit image, in
// place; the same seed gives the same noise. One table look-up per value from a 64-bit counter
// hash (four values per hash), a few times cheaper than cv::RNG's normal fill plus the int16
// round trip, so the simulator's camera keeps 30 Hz with room left for the pipeline.
void addGaussianNoise(double sigma, uint64_t seed, cv::Mat* image);
// The same with the table of roundedGaussianTable(sigma) built once by the caller (a camera
// adds noise of one sigma to every frame). Throws std::invalid_argument for another table size.
void addGaussianNoise(const std::vector<int16_t>& rounded_gaussian_table, uint64_t seed, cv::Mat* image);

}  // namespace rle_vision
