// The ridge fitter's inner loop (private to the core): bilinear edge samples across a line,
// scalar and with AVX2, which must agree bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "common/simd_dispatch.h"

namespace rle_vision {
namespace ridge {

// The bilinear edge values at (bx + offset_x[i], by + offset_y[i]), i < count, all of whose
// 2x2 neighbourhoods are inside the image (truncation is floor).
inline void profileInside(const uint8_t* data, size_t step, double bx, double by, const double* offset_x,
                          const double* offset_y, int count, double* profile) {
  for (int i = 0; i < count; ++i) {
    const double x = bx + offset_x[i], y = by + offset_y[i];
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const double fx = x - x0, fy = y - y0;
    const uint8_t* r0 = data + y0 * step + x0;
    const uint8_t* r1 = r0 + step;
    profile[i] = (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
  }
}

#ifdef RLE_VISION_AVX2_KERNELS
// The same four samples at a time: the same operations in the same order on each lane (AVX2
// without FMA), so the values are bit for bit the scalar ones; only where cpuHasAvx2().
void profileInsideAvx2(const uint8_t* data, size_t step, double bx, double by, const double* offset_x,
                       const double* offset_y, int count, double* profile);
#endif

// profileInside with the fastest kernel this CPU runs.
inline void profileInsideFastest(const uint8_t* data, size_t step, double bx, double by, const double* offset_x,
                                 const double* offset_y, int count, double* profile) {
#ifdef RLE_VISION_AVX2_KERNELS
  if (cpuHasAvx2()) {
    profileInsideAvx2(data, step, bx, by, offset_x, offset_y, count, profile);
    return;
  }
#endif
  profileInside(data, step, bx, by, offset_x, offset_y, count, profile);
}

}  // namespace ridge
}  // namespace rle_vision
