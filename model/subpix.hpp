// Sub-pixel disparity, 4 fractional bits (docs/algorithm.md section 9.1): a fit of three
// aggregated costs around a level, integer arithmetic only.
#pragma once

#include <algorithm>
#include <cstdlib>

#include "evidence.hpp"
#include "output_regs.hpp"

namespace sm {

// Offset of the minimum of the fit through (-1, cm), (0, c0), (1, cp) in 1/16 px, -8..8:
//  parabola   (fit 0): round(16 (cm - cp) / (2 (cm - 2 c0 + cp)))
//  equiangular(fit 1): round(16 (cm - cp) / (2 max(cm - c0, cp - c0)))
// rounded half away from zero, clamped to -8..8; 0 when the denominator is not positive.
inline int fit_q4(int cm, int c0, int cp, int fit) {
  const int num = cm - cp;
  const int den = fit == 0 ? 2 * (cm - 2 * c0 + cp) : 2 * std::max(cm - c0, cp - c0);
  if (den <= 0) return 0;
  // round(16 |num| / den), half up, on the magnitude (a 4-bit restoring division in the RTL)
  const int q = (32 * std::abs(num) + den) / (2 * den);
  const int m = std::min(q, 8);
  return num < 0 ? -m : m;
}

// The Q.4 disparity 16 d + f at the DP's level d (evidence row y, pixel x) by the source
// subpix_src picks (output_regs.hpp); 16 d when the source has no fit there (d or the WTA
// level at 0 or DISP - 1, the DP level outside the stored band) or subpix_en = 0.
inline int subpix_q4(const Evidence& ev, int x, int y, int nd, const OutputRegs& r) {
  const int d = ev.d.at(x, y);
  if (!r.subpix_en) return 16 * d;
  if (r.subpix_src == 0) {
    if (d == 0 || d == nd - 1) return 16 * d;
    return 16 * d + fit_q4(ev.cm.at(x, y), ev.c0.at(x, y), ev.cp.at(x, y), r.subpix_fit);
  }
  const int dw = ev.dw.at(x, y);
  if (r.subpix_src == 1) {
    if (std::abs(d - dw) > 1 || dw == 0 || dw == nd - 1) return 16 * d;
    return 16 * dw + fit_q4(ev.band[1].at(x, y), ev.band[2].at(x, y), ev.band[3].at(x, y), r.subpix_fit);
  }
  const int j = d - dw + 2;  // d's index in the band
  if (j < 1 || j > 3 || d == 0 || d == nd - 1) return 16 * d;
  const auto b = [&](int k) { return static_cast<int>(ev.band[static_cast<size_t>(k)].at(x, y)); };
  return 16 * d + fit_q4(b(j - 1), b(j), b(j + 1), r.subpix_fit);
}

// The output's Q.4 value after the post filters: the DP pixel's value v when the filters
// kept its level (post_d == the DP's level d), else 16 post_d (a level the filters took
// from a neighbour has no fraction).
inline int subpix_after_post(int v, int d, int post_d) { return post_d == d ? v : 16 * post_d; }

}  // namespace sm
