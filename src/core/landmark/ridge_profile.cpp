#include "landmark/ridge_profile.h"

namespace rle_vision {
namespace ridge {

#ifdef RLE_VISION_AVX2_KERNELS
__attribute__((target("avx2"))) void profileInsideAvx2(const uint8_t* data, size_t step, double bx, double by,
                                                        const double* offset_x, const double* offset_y, int count,
                                                        double* profile) {
  const __m256d base_x = _mm256_set1_pd(bx), base_y = _mm256_set1_pd(by), one = _mm256_set1_pd(1.0);
  const __m128i low_byte = _mm_set1_epi32(0xFF);
  int i = 0;
  for (; i + 4 <= count; i += 4) {
    const __m256d x = _mm256_add_pd(base_x, _mm256_loadu_pd(offset_x + i));
    const __m256d y = _mm256_add_pd(base_y, _mm256_loadu_pd(offset_y + i));
    const __m128i xi = _mm256_cvttpd_epi32(x), yi = _mm256_cvttpd_epi32(y);
    const __m256d fx = _mm256_sub_pd(x, _mm256_cvtepi32_pd(xi)), fy = _mm256_sub_pd(y, _mm256_cvtepi32_pd(yi));
    alignas(16) int32_t col[4], row[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(col), xi);
    _mm_store_si128(reinterpret_cast<__m128i*>(row), yi);
    alignas(16) int32_t top[4], bottom[4];  // each pixel pair: left in the low byte, right in the next
    for (int lane = 0; lane < 4; ++lane) {
      const uint8_t* r0 = data + row[lane] * step + col[lane];
      top[lane] = r0[0] | (r0[1] << 8);
      bottom[lane] = r0[step] | (r0[step + 1] << 8);
    }
    const __m128i t = _mm_load_si128(reinterpret_cast<const __m128i*>(top));
    const __m128i b = _mm_load_si128(reinterpret_cast<const __m128i*>(bottom));
    const __m256d v00 = _mm256_cvtepi32_pd(_mm_and_si128(t, low_byte)), v01 = _mm256_cvtepi32_pd(_mm_srli_epi32(t, 8));
    const __m256d v10 = _mm256_cvtepi32_pd(_mm_and_si128(b, low_byte)), v11 = _mm256_cvtepi32_pd(_mm_srli_epi32(b, 8));
    const __m256d gx = _mm256_sub_pd(one, fx), gy = _mm256_sub_pd(one, fy);
    const __m256d upper = _mm256_add_pd(_mm256_mul_pd(gx, v00), _mm256_mul_pd(fx, v01));
    const __m256d lower = _mm256_add_pd(_mm256_mul_pd(gx, v10), _mm256_mul_pd(fx, v11));
    _mm256_storeu_pd(profile + i, _mm256_add_pd(_mm256_mul_pd(gy, upper), _mm256_mul_pd(fy, lower)));
  }
  profileInside(data, step, bx, by, offset_x + i, offset_y + i, count - i, profile + i);
}
#endif

}  // namespace ridge
}  // namespace rle_vision
