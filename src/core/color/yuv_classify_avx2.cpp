#include "color/yuv_classify_avx2.h"

#include "rle_vision/color/color_convert.h"

#include "common/simd_dispatch.h"

namespace rle_vision {

#ifdef RLE_VISION_AVX2_KERNELS

bool yuvClassifyAvx2Available() { return cpuHasAvx2(); }

namespace {

#define RLE_VISION_AVX2 __attribute__((target("avx2")))

// Y, U, V (int16) of 16 pixels given as int16 r, g, b. Same fixed point as OpenCV:
// y = (r*R2Y + g*G2Y + b*B2Y + round) >> 14, u = ((b - y)*B2U + round) >> 14 + 128 (v alike).
// For u and v, mulhrs on twice the difference gives exactly (d*c + 2^13) >> 14: it computes
// (2d*c + 2^14) >> 15, with no unpacking to 32 bits.
RLE_VISION_AVX2 inline void yuv16(__m256i r, __m256i g, __m256i b, __m256i* y, __m256i* u,
                                  __m256i* v) {
  using namespace yuv_fixed_point;
  static_assert(kRound == 1 << 13 && kShift == 14, "the mulhrs form needs the 14-bit fixed point");
  const __m256i one = _mm256_set1_epi16(1);
  const __m256i c_rg = _mm256_set1_epi32((kG2Y << 16) | kR2Y);       // pairs (r, g)
  const __m256i c_b1 = _mm256_set1_epi32((kRound << 16) | kB2Y);     // pairs (b, 1)
  const __m256i y_lo = _mm256_srai_epi32(
      _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpacklo_epi16(r, g), c_rg),
                       _mm256_madd_epi16(_mm256_unpacklo_epi16(b, one), c_b1)), kShift);
  const __m256i y_hi = _mm256_srai_epi32(
      _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpackhi_epi16(r, g), c_rg),
                       _mm256_madd_epi16(_mm256_unpackhi_epi16(b, one), c_b1)), kShift);
  *y = _mm256_packs_epi32(y_lo, y_hi);  // unpack/pack are both per 128-bit lane: order kept
  const __m256i by = _mm256_sub_epi16(b, *y);
  const __m256i ry = _mm256_sub_epi16(r, *y);
  const __m256i offset = _mm256_set1_epi16(128);
  *u = _mm256_add_epi16(_mm256_mulhrs_epi16(_mm256_add_epi16(by, by), _mm256_set1_epi16(kB2U)), offset);
  *v = _mm256_add_epi16(_mm256_mulhrs_epi16(_mm256_add_epi16(ry, ry), _mm256_set1_epi16(kR2V)), offset);
}

// Two groups of 16 int16 values (0..255 after saturation) to 32 bytes in pixel order.
RLE_VISION_AVX2 inline __m256i packBytes(__m256i first16, __m256i second16) {
  return _mm256_permute4x64_epi64(_mm256_packus_epi16(first16, second16), 0xD8);
}

// x in [lo, lo + span] (mod 256), per byte.
RLE_VISION_AVX2 inline __m256i inBox(__m256i x, __m256i lo, __m256i span) {
  const __m256i d = _mm256_sub_epi8(x, lo);
  return _mm256_cmpeq_epi8(_mm256_min_epu8(d, span), d);
}

// The class boxes as byte vectors, made once per row instead of once per 32 pixels (the
// broadcasts compete with the conversion's shuffles for one execution port).
struct BoxVectors {
  explicit RLE_VISION_AVX2 BoxVectors(const YuvBoxes& boxes) : count(boxes.count) {
    for (int k = 0; k < count; ++k) {
      for (int ch = 0; ch < 3; ++ch) {
        lo[k][ch] = _mm256_set1_epi8(static_cast<char>(boxes.lo[k][ch]));
        span[k][ch] = _mm256_set1_epi8(static_cast<char>(boxes.span[k][ch]));
      }
      label[k] = _mm256_set1_epi8(static_cast<char>(boxes.label[k]));
    }
  }
  int count;
  __m256i lo[kMaxColorClasses][3], span[kMaxColorClasses][3], label[kMaxColorClasses];
};

// Labels of 32 pixels from their Y, U, V bytes: later boxes overwrite earlier ones.
RLE_VISION_AVX2 inline __m256i labelsOf(__m256i y, __m256i u, __m256i v, const BoxVectors& boxes) {
  __m256i label = _mm256_setzero_si256();
  for (int k = 0; k < boxes.count; ++k) {
    const __m256i inside = _mm256_and_si256(
        _mm256_and_si256(inBox(y, boxes.lo[k][0], boxes.span[k][0]), inBox(u, boxes.lo[k][1], boxes.span[k][1])),
        inBox(v, boxes.lo[k][2], boxes.span[k][2]));
    label = _mm256_blendv_epi8(label, boxes.label[k], inside);
  }
  return label;
}

// pshufb mask taking, from each 16-byte lane of 4:2:2 data (8 pixels), the byte at `offset`
// of every pixel (Y: step 2) or of every pixel pair, repeated (chroma: step 4), into the low
// or the high 8 bytes of the lane.
RLE_VISION_AVX2 inline __m256i gatherMask(int offset, bool chroma, bool high) {
  alignas(16) int8_t m[16];
  for (int i = 0; i < 16; ++i) m[i] = -1;
  for (int i = 0; i < 8; ++i) {
    m[(high ? 8 : 0) + i] = static_cast<int8_t>(offset + (chroma ? 4 * (i / 2) : 2 * i));
  }
  return _mm256_broadcastsi128_si256(_mm_load_si128(reinterpret_cast<const __m128i*>(m)));
}

// Scalar label of one pixel (row tails).
inline uint8_t labelOf(const Channels& yuv, const YuvBoxes& boxes) {
  uint8_t label = 0;
  for (int k = 0; k < boxes.count; ++k) {
    bool inside = true;
    for (int ch = 0; ch < 3; ++ch) {
      inside = inside && static_cast<uint8_t>(yuv[ch] - boxes.lo[k][ch]) <= boxes.span[k][ch];
    }
    if (inside) label = boxes.label[k];
  }
  return label;
}

}  // namespace

RLE_VISION_AVX2
void classifyRowYuv422Avx2(const uint8_t* src, int width, bool is_uyvy, const YuvBoxes& boxes,
                           uint8_t* labels) {
  // Per 128-bit lane (8 pixels = 16 bytes): gather Y, and U and V repeated for each pixel of a
  // pair, into the low 8 bytes (first load) or the high 8 bytes (second load).
  const int yo = is_uyvy ? 1 : 0, uo = is_uyvy ? 0 : 1, vo = uo + 2;
  const __m256i y_lo = gatherMask(yo, false, false), y_hi = gatherMask(yo, false, true);
  const __m256i u_lo = gatherMask(uo, true, false), u_hi = gatherMask(uo, true, true);
  const __m256i v_lo = gatherMask(vo, true, false), v_hi = gatherMask(vo, true, true);
  const BoxVectors box_vectors(boxes);
  int x = 0;
  for (; x + 32 <= width; x += 32) {
    // a: pixels x..x+15 (lanes: x..x+7 | x+8..x+15), b: pixels x+16..x+31.
    const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + 2 * x));
    const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + 2 * x + 32));
    // Lanes now hold pixels (x..x+7, x+16..x+23 | x+8..x+15, x+24..x+31): reorder the quarters.
    const __m256i y = _mm256_permute4x64_epi64(_mm256_or_si256(_mm256_shuffle_epi8(a, y_lo), _mm256_shuffle_epi8(b, y_hi)), 0xD8);
    const __m256i u = _mm256_permute4x64_epi64(_mm256_or_si256(_mm256_shuffle_epi8(a, u_lo), _mm256_shuffle_epi8(b, u_hi)), 0xD8);
    const __m256i v = _mm256_permute4x64_epi64(_mm256_or_si256(_mm256_shuffle_epi8(a, v_lo), _mm256_shuffle_epi8(b, v_hi)), 0xD8);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(labels + x), labelsOf(y, u, v, box_vectors));
  }
  for (; x < width; ++x) {
    const uint8_t* pair = src + 4 * (x / 2);
    labels[x] = labelOf(Channels{{pair[yo + 2 * (x % 2)], pair[uo], pair[vo]}}, boxes);
  }
}

RLE_VISION_AVX2
void classifyRowYuvAvx2(const uint8_t* src, int width, bool src_is_rgb, bool pair_chroma, const YuvBoxes& boxes,
                        uint8_t* labels) {
  // pshufb masks gathering one channel of 16 pixels from three 16-byte blocks (-1: zero).
  const __m256i first_a = _mm256_broadcastsi128_si256(_mm_setr_epi8(0, 3, 6, 9, 12, 15, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1));
  const __m256i first_b = _mm256_broadcastsi128_si256(_mm_setr_epi8(-1, -1, -1, -1, -1, -1, 2, 5, 8, 11, 14, -1, -1, -1, -1, -1));
  const __m256i first_c = _mm256_broadcastsi128_si256(_mm_setr_epi8(-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 1, 4, 7, 10, 13));
  const __m256i mid_a = _mm256_broadcastsi128_si256(_mm_setr_epi8(1, 4, 7, 10, 13, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1));
  const __m256i mid_b = _mm256_broadcastsi128_si256(_mm_setr_epi8(-1, -1, -1, -1, -1, 0, 3, 6, 9, 12, 15, -1, -1, -1, -1, -1));
  const __m256i mid_c = _mm256_broadcastsi128_si256(_mm_setr_epi8(-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 2, 5, 8, 11, 14));
  const __m256i last_a = _mm256_broadcastsi128_si256(_mm_setr_epi8(2, 5, 8, 11, 14, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1));
  const __m256i last_b = _mm256_broadcastsi128_si256(_mm_setr_epi8(-1, -1, -1, -1, -1, 1, 4, 7, 10, 13, -1, -1, -1, -1, -1, -1));
  const __m256i last_c = _mm256_broadcastsi128_si256(_mm_setr_epi8(-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 3, 6, 9, 12, 15));

  // Swaps the bytes of each pixel pair: averaged with the original, both get the pair's mean.
  const __m256i pair_swap = _mm256_broadcastsi128_si256(_mm_setr_epi8(1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14));
  const BoxVectors box_vectors(boxes);
  int x = 0;
  for (; x + 32 <= width; x += 32) {
    const uint8_t* p = src + 3 * x;
    // Lane 0 holds pixels x..x+15, lane 1 pixels x+16..x+31.
    const __m256i a = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))),
                                              _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 48)), 1);
    const __m256i b = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16))),
                                              _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 64)), 1);
    const __m256i c = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 32))),
                                              _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 80)), 1);
    const __m256i first = _mm256_or_si256(_mm256_or_si256(_mm256_shuffle_epi8(a, first_a), _mm256_shuffle_epi8(b, first_b)),
                                          _mm256_shuffle_epi8(c, first_c));
    const __m256i mid = _mm256_or_si256(_mm256_or_si256(_mm256_shuffle_epi8(a, mid_a), _mm256_shuffle_epi8(b, mid_b)),
                                        _mm256_shuffle_epi8(c, mid_c));
    const __m256i last = _mm256_or_si256(_mm256_or_si256(_mm256_shuffle_epi8(a, last_a), _mm256_shuffle_epi8(b, last_b)),
                                         _mm256_shuffle_epi8(c, last_c));
    const __m256i blue8 = src_is_rgb ? last : first;
    const __m256i red8 = src_is_rgb ? first : last;
    __m256i y0, u0, v0, y1, u1, v1;
    yuv16(_mm256_cvtepu8_epi16(_mm256_castsi256_si128(red8)), _mm256_cvtepu8_epi16(_mm256_castsi256_si128(mid)),
          _mm256_cvtepu8_epi16(_mm256_castsi256_si128(blue8)), &y0, &u0, &v0);
    yuv16(_mm256_cvtepu8_epi16(_mm256_extracti128_si256(red8, 1)), _mm256_cvtepu8_epi16(_mm256_extracti128_si256(mid, 1)),
          _mm256_cvtepu8_epi16(_mm256_extracti128_si256(blue8, 1)), &y1, &u1, &v1);
    __m256i u = packBytes(u0, u1), v = packBytes(v0, v1);
    if (pair_chroma) {
      u = _mm256_avg_epu8(u, _mm256_shuffle_epi8(u, pair_swap));
      v = _mm256_avg_epu8(v, _mm256_shuffle_epi8(v, pair_swap));
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(labels + x), labelsOf(packBytes(y0, y1), u, v, box_vectors));
  }
  // The last < 32 pixels (x even: pairs as above), scalar.
  const int r_index = src_is_rgb ? 0 : 2;
  for (; x < width; x += 2) {
    const uint8_t* p = src + 3 * x;
    Channels first = yuvFromRgb(p[r_index], p[1], p[2 - r_index]);
    if (x + 1 == width) {
      labels[x] = labelOf(first, boxes);
      break;
    }
    Channels second = yuvFromRgb(p[3 + r_index], p[4], p[5 - r_index]);
    if (pair_chroma) {
      for (int ch = 1; ch < 3; ++ch) {
        first[ch] = second[ch] = pairMean(first[ch], second[ch]);
      }
    }
    labels[x] = labelOf(first, boxes);
    labels[x + 1] = labelOf(second, boxes);
  }
}

#else  // no AVX2 kernel on this platform

bool yuvClassifyAvx2Available() { return false; }
void classifyRowYuvAvx2(const uint8_t*, int, bool, bool, const YuvBoxes&, uint8_t*) {}
void classifyRowYuv422Avx2(const uint8_t*, int, bool, const YuvBoxes&, uint8_t*) {}

#endif

}  // namespace rle_vision
