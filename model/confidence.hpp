// Per-pixel confidence of the output stage (docs/algorithm.md section 9.3): 8 bits, higher
// = more likely right, from quantities the RTL has per pixel (the evidence record).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "evidence.hpp"

namespace sm {

// Confidence of pixel (x, y) whose output level is d_out (variant 0, the specified one):
//   bit 7    left-right consistent: |right WTA of x - d  -  d| <= 1   (d: the DP's level)
//   bit 6    matched by the trellis and x >= d_out
//   bit 5    |d - WTA level| <= 1
//   bits 4:0 min(31, floor(32 (C2 - C1) / (C2 + 1)))                 (WTA uniqueness ratio)
// Variants 1..3 are the alternatives sm_output_study measures against it.
inline uint8_t confidence(const Evidence& ev, int x, int y, int d_out, int variant = 0) {
  const int d = ev.d.at(x, y), c1 = ev.c1.at(x, y), c2 = ev.c2.at(x, y);
  const bool lr = std::abs(static_cast<int>(ev.lr.at(x, y)) - d) <= 1;
  const bool sure = ev.matched.at(x, y) && x >= d_out;
  const bool agree = std::abs(d - static_cast<int>(ev.dw.at(x, y))) <= 1;
  const int ratio = std::min(31, 32 * (c2 - c1) / (c2 + 1));  // 5-bit (C2 - C1) / (C2 + 1)
  switch (variant) {
    case 1:  // the WTA margin alone
      return static_cast<uint8_t>(std::min(255, 4 * (c2 - c1)));
    case 2:  // without the left-right bit
      return static_cast<uint8_t>(sure << 7 | agree << 6 | ratio << 1);
    case 3:  // the margin in place of the ratio
      return static_cast<uint8_t>(lr << 7 | sure << 6 | agree << 5 | std::min(31, c2 - c1));
    default:
      return static_cast<uint8_t>(lr << 7 | sure << 6 | agree << 5 | ratio);
  }
}
constexpr int kConfidenceVariants = 4;

}  // namespace sm
