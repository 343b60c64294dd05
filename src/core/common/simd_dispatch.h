// Hot loops are written as plain loops the compiler vectorises; on x86-64 Linux each one is
// also cloned for AVX2 and picked at load time, so one binary is fast on new CPUs and still
// runs on any x86-64 (and on ARM, where only the default version is built).
#pragma once

#if defined(__x86_64__) && defined(__linux__) && !defined(RLE_VISION_NO_MULTIVERSION) && \
    (defined(__clang__) ? (__clang_major__ >= 14) : defined(__GNUC__))
#define RLE_VISION_HOT __attribute__((target_clones("avx2", "default")))
#else
#define RLE_VISION_HOT
#endif

// Kernels written with AVX2 intrinsics (in functions marked __attribute__((target("avx2")))),
// built on x86-64 and called only where cpuHasAvx2() says the CPU runs them.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(RLE_VISION_NO_MULTIVERSION)
#define RLE_VISION_AVX2_KERNELS 1
#include <immintrin.h>

namespace rle_vision {

// True when this CPU runs AVX2 (checked once).
inline bool cpuHasAvx2() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

}  // namespace rle_vision
#endif
