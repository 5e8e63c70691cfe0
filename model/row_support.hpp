// The row support of the stream's confidence (docs/algorithm.md 9.7), rtl/sm_out_support.v:
// after the smoothing, a valid word's confidence c becomes min(255, c + 5 R), R the words
// at +-3, +-6, .. +-15 columns in its own row (inside the row) that are valid with a Q.4
// value within 16 (one pixel) of its own. A mismatch island of one wrong level is often
// wider than the smoothing's 5x5 window but narrower than the surfaces around it; samples
// further along the row tell it apart (sm_output_study --study window-conf). Invalid
// words pass as they are.
#pragma once

#include "outword.hpp"

namespace sm {

constexpr int kRowSupportStep = 3;    // columns between the row's samples
constexpr int kRowSupportReach = 15;  // the farthest sample, each side
constexpr int kRowSupportTol = 16;    // a sample supports the centre within one pixel (Q.4)
constexpr int kRowSupportWeight = 5;  // the confidence gains this per supporting sample

// R of the valid word at (x, y): 0 .. 2 kRowSupportReach / kRowSupportStep.
int row_support(const OutImage& in, int x, int y);

// The words of in with every valid word's confidence raised by its row support. With
// threads > 1 the rows are split into bands (the same words for any thread count).
OutImage row_support_output(const OutImage& in, int threads = 1);

}  // namespace sm
