// The output words' edge-preserving smoothing (docs/algorithm.md 9.7), rtl/sm_out_smooth.v:
// a valid pixel's Q.4 disparity becomes the rounded mean of the valid pixels of its 5x5
// window (inside the frame) whose Q.4 value is within smooth_t of its own. The fraction a
// single pixel's cost curve gives is noisy; its neighbours on the same surface average
// the noise out, and the threshold keeps the mean from crossing a depth edge.
#pragma once

#include <cstdint>

#include "outword.hpp"

namespace sm {

constexpr int kSmoothR = 2;  // window rows (and columns) on each side of the centre

// The rounded mean's offset from the centre, floor(s / k + 1/2): s the sum of the k
// window values' differences from the centre (k >= 1, the centre among them).
int smooth_offset(int s, int k);

// The words of in with every valid pixel's Q.4 value smoothed (smooth_en 0: in itself);
// the valid bit and the confidence are the input's. With threads > 1 the rows are split
// into bands (the same words for any thread count).
OutImage smooth_output(const OutImage& in, int smooth_en, int smooth_t, int threads = 1);

// The words the IP streams out: make_output's words, smoothed as r says.
OutImage stream_words(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int threads = 1);

}  // namespace sm
