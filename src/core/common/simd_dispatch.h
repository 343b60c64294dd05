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
