// The flip filter of appendRowRuns computed 64 pixels at a time, for noisy rows: there the
// filter's step per stretch start (tens of thousands a frame) is what the encoder costs.
#pragma once

#include <cstdint>

#include "segment/row_encoders.h"

namespace rle_vision {

// The largest max_flip_px the word-parallel filter takes (the parameter's own maximum).
constexpr int kMaxWordFlipPx = 8;

// A row is noisy, and the words pay, from one stretch start per this many pixels: below, the
// filter's step per start costs less than the words' fixed work. Measured on the bench's 8
// noise fields, UYVY: at one per 32 pixels σ = 60 took 0.35 ms, at one per 16 0.36 ms, the
// clean and σ = 25 frames the same; at one per 64 the clean frame began to cost more.
constexpr int kNoisyRowPixelsPerStart = 32;
inline bool isNoisyRow(int stretch_starts, int width) { return stretch_starts * kNoisyRowPixelsPerStart >= width; }

// True when this CPU runs the word-parallel filter (AVX2, checked once).
bool flipFilterWordsAvailable();

// Writes the runs of one row of labels with the flip filter (max_flip_px in 1..kMaxWordFlipPx)
// to `buffer` and returns how many were kept: the same runs as FlipFilterRow on every stretch
// start. A row that turns out not noisy goes through FlipFilterRow. `stretch_starts`: the row's
// stretch starts, the first pixel included. Only call when flipFilterWordsAvailable().
int32_t encodeFlipFilterRowWords(const uint8_t* labels, int width, int max_flip_px, row_encoding::RowBuffer buffer,
                                 FlipFilterWordBuffers* buffers, int* stretch_starts);

}  // namespace rle_vision
