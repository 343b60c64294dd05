// Fused BGR/RGB -> YUV -> class-label kernel for AVX2 CPUs: the tracker's hot path when all
// classes are YUV boxes (the default). Bit-exact with bgrRowToYuvPlanes + the box compares.
#pragma once

#include <cstdint>

namespace rle_vision {

// YUV class boxes in application order: the kernel applies entry 0 first and later entries
// overwrite, so callers list classes from lowest to highest priority.
struct YuvBoxes {
  int count = 0;
  uint8_t lo[32][3];
  uint8_t span[32][3];  // max - min (mod 256: wrapped ranges work)
  uint8_t label[32];
};

// True when this CPU runs the AVX2 kernel (checked once).
bool yuvClassifyAvx2Available();

// Labels `width` pixels of an interleaved 8-bit row (B,G,R order, or R,G,B when src_is_rgb).
// With `pair_chroma`, each pixel pair (0-1, 2-3, ...) is classified on its mean U and V,
// (a + b + 1) / 2, as 4:2:2 sends them (a last odd pixel keeps its own).
// Only call when yuvClassifyAvx2Available().
void classifyRowYuvAvx2(const uint8_t* src, int width, bool src_is_rgb, bool pair_chroma, const YuvBoxes& boxes,
                        uint8_t* labels);

// The same for a 4:2:2 row (UYVY, or YUYV when !is_uyvy): each pixel pair shares its U and V.
void classifyRowYuv422Avx2(const uint8_t* src, int width, bool is_uyvy, const YuvBoxes& boxes,
                           uint8_t* labels);

}  // namespace rle_vision
