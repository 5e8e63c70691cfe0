// The output words' window stage (docs/algorithm.md 9.7), rtl/sm_out_smooth.v: a valid
// pixel's Q.4 disparity becomes the rounded mean of the valid pixels of its 5x5 window
// (inside the frame) whose Q.4 value is within smooth_t of its own. The fraction a single
// pixel's cost curve gives is noisy; its neighbours on the same surface average the noise
// out, and the threshold keeps the mean from crossing a depth edge. How many neighbours
// agree with the pixel is evidence too: the confidence adds it.
#pragma once

#include <cstdint>

#include "outword.hpp"

namespace sm {

constexpr int kSmoothR = 2;      // window rows (and columns) on each side of the centre
constexpr int kSupportNear = 8;  // the confidence's second support count: within 1/2 pixel

// The rounded mean's offset from the centre, floor(s / k + 1/2): s the sum of the k
// window values' differences from the centre (k >= 1, the centre among them).
int smooth_offset(int s, int k);

// The stream's confidence (docs/algorithm.md 9.7) from the pixel's evidence byte e (9.3) and
// its window's support: k the window pixels the mean takes (within smooth_t, the centre
// among them), k_near those within kSupportNear. 5 .. 204; the order, not the value, is
// what the weights (chosen on the 14 scenes) fix.
inline uint8_t support_confidence(unsigned e, int k, int k_near) {
  return static_cast<uint8_t>(16 * (e >> 7 & 1) + 16 * (e >> 6 & 1) + 16 * (e >> 5 & 1) + (e & 31) + 3 * k +
                              2 * k_near);
}

// The words of in with every valid pixel's Q.4 value smoothed (smooth_en 0: unchanged) and
// its confidence byte replaced by support_confidence (also with smooth_en 0); invalid words
// pass as they are. With threads > 1 the rows are split into bands (the same words for any
// thread count).
OutImage smooth_output(const OutImage& in, int smooth_en, int smooth_t, int threads = 1);

// The output stage's window stages as the IP runs them on the words (9.7): the smoothing
// (smooth_output), then the row support of the confidence (row_support.hpp).
OutImage smooth_stream(const OutImage& in, int smooth_en, int smooth_t, int threads = 1);

// The words the IP streams out: make_output's words through smooth_stream as r says.
OutImage stream_words(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int threads = 1);

}  // namespace sm
