// Sub-pixel disparity, 4 fractional bits (docs/algorithm.md section 9.1): a fit of three
// aggregated costs around a level, integer arithmetic only.
#pragma once

#include "evidence.hpp"
#include "output_regs.hpp"

namespace sm {

// Offset of the minimum of the fit through (-1, cm), (0, c0), (1, cp) in 1/16 px, -8..8:
//  parabola   (fit 0): round(16 (cm - cp) / (2 (cm - 2 c0 + cp)))
//  equiangular(fit 1): round(16 (cm - cp) / (2 max(cm - c0, cp - c0)))
// rounded half away from zero, clamped to -8..8; 0 when the denominator is not positive.
int fit_q4(int cm, int c0, int cp, int fit);

// The Q.4 disparity 16 d + f at the DP's level d (evidence row y, pixel x) by the source
// subpix_src picks (output_regs.hpp); 16 d when the source has no fit there (d or the WTA
// level at 0 or DISP - 1, the DP level outside the stored band) or subpix_en = 0.
int subpix_q4(const Evidence& ev, int x, int y, int nd, const OutputRegs& r);

// The output's Q.4 value after the post filters: the DP pixel's value v when the filters
// kept its level (post_d == the DP's level d), else 16 post_d (a level the filters took
// from a neighbour has no fraction).
int subpix_after_post(int v, int d, int post_d);

}  // namespace sm
