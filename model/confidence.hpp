// Per-pixel confidence of the output stage (docs/algorithm.md section 9.3): 8 bits, higher
// = more likely right, from quantities the RTL has per pixel (the evidence record).
#pragma once

#include <cstdint>

#include "evidence.hpp"

namespace sm {

// Confidence of pixel (x, y) whose output level is d_out (variant 0, the specified one):
//   bit 7    left-right consistent: |right WTA of x - d  -  d| <= 1   (d: the DP's level)
//   bit 6    matched by the trellis and x >= d_out
//   bit 5    |d - WTA level| <= 1
//   bits 4:0 min(31, floor(32 (C2 - C1) / (C2 + 1)))                 (WTA uniqueness ratio)
// Variants 1..3 are the alternatives sm_output_study measures against it.
uint8_t confidence(const Evidence& ev, int x, int y, int d_out, int variant = 0);
constexpr int kConfidenceVariants = 4;

}  // namespace sm
