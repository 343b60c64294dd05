#include "segment/flip_filter_words.h"

#include <cstring>
#include <vector>

#include "common/simd_dispatch.h"

namespace rle_vision {

#ifdef RLE_VISION_AVX2_KERNELS

bool flipFilterWordsAvailable() { return cpuHasAvx2(); }

namespace {

// How the filter reads on stretches s_0 .. s_n-1 of a row: FlipFilterRow joins a short s_j
// (0 < j < n - 1) to s_j-1 and s_j+1 when those share a label, unless s_j-1 was itself joined
// that way (then s_j+1 joined it, and the filter looks at s_j+2 next). So in a chain of
// consecutive such candidates every other one is joined, starting with the chain's first: a
// candidate is joined when its index has the parity of its chain's first. Here every pixel is a
// bit: stretch starts, candidates (at their starts), chains (every pixel of a candidate), the
// index parity (a prefix XOR of the starts), and the parity of each chain's first spread over
// the chain by the carry of one addition. A run starts at every stretch start but those of the
// joined stretches and of the stretches right after them.

// Bits x + j of `bits` for the pixels of word w (j in 0..63; `bits` has a word after w).
inline uint64_t bitsAfter(const uint64_t* bits, int w, int j) {
  return j == 0 ? bits[w] : (bits[w] >> j) | (bits[w + 1] << (64 - j));
}

// Each bit: the parity of the set bits at or below it.
inline uint64_t prefixParity(uint64_t v) {
  v ^= v << 1;
  v ^= v << 2;
  v ^= v << 4;
  v ^= v << 8;
  v ^= v << 16;
  v ^= v << 32;
  return v;
}

// Bit x of out[w]: a[64w + x] == b[64w + x], for `words` words.
__attribute__((target("avx2"))) void equalBits(const uint8_t* a, const uint8_t* b, int words, uint64_t* out) {
  for (int w = 0; w < words; ++w) {
    const __m256i a0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + 64 * w));
    const __m256i b0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + 64 * w));
    const __m256i a1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + 64 * w + 32));
    const __m256i b1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + 64 * w + 32));
    const uint32_t low = static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(a0, b0)));
    const uint32_t high = static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(a1, b1)));
    out[w] = low | (uint64_t{high} << 32);
  }
}

// Bits of word w at pixels below `limit` (all, none or the low ones).
inline uint64_t belowMask(int w, int limit) {
  const int first = 64 * w;
  if (limit <= first) return 0;
  if (limit >= first + 64) return ~uint64_t{0};
  return (uint64_t{1} << (limit - first)) - 1;
}

// The stretch starts of a row (bit 0 set; pixels from `width` on set too, so the last stretch
// ends there); returns how many starts lie in the row, the first pixel's included.
int stretchStarts(const uint8_t* row, int width, int words, uint64_t* starts) {
  equalBits(row, row - 1, words, starts);
  int count = 0;
  for (int w = 0; w < words; ++w) {
    starts[w] = ~starts[w] | ~belowMask(w, width);
    if (w == 0) starts[0] |= 1;  // row[-1] is padding
    count += __builtin_popcountll(starts[w] & belowMask(w, width));
  }
  starts[words] = ~uint64_t{0};
  return count;
}

// The candidates of length exactly m, per m, and the run starts kept; `equal` holds, per m,
// bit x = row[x - 1] == row[x + m] with x + m inside the row and x > 0.
template <int kMaxFlip>
void keptRunStarts(const uint64_t* starts, const uint64_t* equal, int words, uint64_t* kept) {
  uint64_t previous_candidates[kMaxFlip + 1] = {};
  uint64_t previous_joined[kMaxFlip + 1] = {};
  bool parity_carry = false, chain_carry = false, first_parity_carry = false;
  for (int w = 0; w < words; ++w) {
    uint64_t candidates_of_length[kMaxFlip + 1];
    uint64_t candidates = 0, chain = 0;
    uint64_t no_start_inside = ~uint64_t{0};  // no stretch start at x + 1 .. x + m - 1
    for (int m = 1; m <= kMaxFlip; ++m) {
      if (m > 1) no_start_inside &= ~bitsAfter(starts, w, m - 1);
      const uint64_t found = starts[w] & no_start_inside & bitsAfter(starts, w, m) & equal[(m - 1) * words + w];
      candidates_of_length[m] = found;
      candidates |= found;
      uint64_t pixels = found;  // the candidate's m pixels, some of them in the next word
      for (int i = 1; i < m; ++i) pixels |= (found << i) | (previous_candidates[m] >> (64 - i));
      chain |= pixels;
      previous_candidates[m] = found;
    }
    const uint64_t parity = prefixParity(starts[w]) ^ (parity_carry ? ~uint64_t{0} : 0);
    // Chains whose first candidate has its parity bit set: adding their first bit clears them,
    // which marks their every pixel. A candidate is joined where its parity is its chain's first's.
    uint64_t set_firsts = chain & ~((chain << 1) | static_cast<uint64_t>(chain_carry)) & parity;
    if (chain_carry && first_parity_carry) set_firsts |= 1;
    const uint64_t set_chains = chain & ~(chain + set_firsts);
    const uint64_t joined = candidates & ~(parity ^ set_chains);
    uint64_t dropped = joined;
    for (int m = 1; m <= kMaxFlip; ++m) {
      const uint64_t joined_m = joined & candidates_of_length[m];
      dropped |= (joined_m << m) | (previous_joined[m] >> (64 - m));
      previous_joined[m] = joined_m;
    }
    kept[w] = starts[w] & ~dropped;
    parity_carry = parity >> 63;
    chain_carry = chain >> 63;
    first_parity_carry = set_chains >> 63;
  }
}

// Walks the set bits below `width` (bit 0 excluded) into `row`.
template <typename Row>
int32_t walkStarts(const uint64_t* starts, int width, int words, Row row) {
  for (int w = 0; w < words; ++w) {
    uint64_t bits = starts[w] & belowMask(w, width);
    if (w == 0) bits &= ~uint64_t{1};
    for (; bits != 0; bits &= bits - 1) row.changeAt(64 * w + __builtin_ctzll(bits));
  }
  return row.finish(width);
}

template <int kMaxFlip>
int32_t encodeWords(const uint8_t* labels, int width, row_encoding::RowBuffer buffer, FlipFilterWordBuffers* buffers,
                    int* stretch_starts) {
  const int words = (width + 63) / 64;
  // Every word reads the 64 labels from its first pixel on, one before and kMaxFlip after.
  constexpr int kBefore = 64;
  buffers->padded_labels.resize(static_cast<size_t>(kBefore + 64 * words + 64 + kMaxFlip));
  uint8_t* row = buffers->padded_labels.data() + kBefore;
  std::memcpy(row, labels, static_cast<size_t>(width));
  buffers->bits.resize(static_cast<size_t>(words) * (kMaxFlip + 2) + 1);
  uint64_t* starts = buffers->bits.data();  // words + 1
  uint64_t* kept = starts + words + 1;
  uint64_t* equal = kept + words;  // kMaxFlip x words
  *stretch_starts = stretchStarts(row, width, words, starts);
  if (!isNoisyRow(*stretch_starts, width)) {
    return walkStarts(starts, width, words, row_encoding::FlipFilterRow(row, kMaxFlip, buffer));
  }
  for (int m = 1; m <= kMaxFlip; ++m) {
    uint64_t* equal_m = equal + (m - 1) * words;
    equalBits(row - 1, row + m, words, equal_m);
    for (int w = 0; w < words; ++w) equal_m[w] &= belowMask(w, width - m);
    equal_m[0] &= ~uint64_t{1};
  }
  keptRunStarts<kMaxFlip>(starts, equal, words, kept);
  return walkStarts(kept, width, words, row_encoding::PlainRow(row, buffer));
}

}  // namespace

int32_t encodeFlipFilterRowWords(const uint8_t* labels, int width, int max_flip_px, row_encoding::RowBuffer buffer,
                                 FlipFilterWordBuffers* buffers, int* stretch_starts) {
  switch (max_flip_px) {
    case 1: return encodeWords<1>(labels, width, buffer, buffers, stretch_starts);
    case 2: return encodeWords<2>(labels, width, buffer, buffers, stretch_starts);
    case 3: return encodeWords<3>(labels, width, buffer, buffers, stretch_starts);
    case 4: return encodeWords<4>(labels, width, buffer, buffers, stretch_starts);
    case 5: return encodeWords<5>(labels, width, buffer, buffers, stretch_starts);
    case 6: return encodeWords<6>(labels, width, buffer, buffers, stretch_starts);
    case 7: return encodeWords<7>(labels, width, buffer, buffers, stretch_starts);
    default: return encodeWords<kMaxWordFlipPx>(labels, width, buffer, buffers, stretch_starts);
  }
}

#else

bool flipFilterWordsAvailable() { return false; }

int32_t encodeFlipFilterRowWords(const uint8_t*, int, int, row_encoding::RowBuffer, FlipFilterWordBuffers*, int*) {
  return 0;
}

#endif

}  // namespace rle_vision
