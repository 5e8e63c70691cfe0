// Per-pixel evidence of the output stage (docs/algorithm.md section 9): what the RTL keeps
// per pixel beside the DP, taken from the aggregated costs of the line as they stream into
// the DP (the WTA record) and from the DP's traceback (level, matched, background fill).
#pragma once

#include <array>
#include <cstdint>

#include "dp.hpp"
#include "sm_types.hpp"

namespace sm {

struct Evidence {
  Image8 d;                    // the DP's level after the fill (DpLine::disp)
  Image8 matched;              // 1: matched by the trellis, 0: unmatched (filled)
  Image8 gap;                  // unmatched: |right match - left match| of its run (255 when the run touches a
                               // line end); matched: 0
  Image8 fill_bg;              // unmatched: min(left match, every match right of x) (0 if none); matched: d
  Image8 cm, c0, cp;           // A(x, d-1), A(x, d), A(x, d+1) at the DP's level (0 outside 0..DISP-1)
  Image8 dw;                   // WTA level: the lowest level of least A(x, .)
  Image8 c1, c2;               // A(x, dw); least A(x, k) over |k - dw| >= 2 (C1 when no such level)
  Image8 cmax;                 // greatest A(x, .)
  Image8 lr;                   // right-view WTA level of right pixel x - d (the lowest k of least
                               // A(x - d + k, k)); 255 when x < d
  std::array<Image8, 5> band;  // A(x, dw - 2 .. dw + 2) (0 outside 0..DISP-1)
  Evidence() = default;
  Evidence(int w, int h);
};

// Row y of the evidence from the line's aggregated costs agg[x * nd + k] and its DP
// result (line.match, line.disp).
void evidence_line(const uint8_t* agg, int w, int nd, const DpLine& line, int y, Evidence& ev);

// The evidence of a whole frame from its aggregated costs: each row's trellis DP (with the
// edge-dependent penalties of the rectified left image, as trellis_dp_edge) traced again
// for its matches, then evidence_line. The stage function run_frame_stages composes.
Evidence evidence_frame(const CostVolume& agg, const Image8& left, uint8_t occ, uint8_t occ_edge, uint8_t edge_t,
                        const HwConfig& hw);

// WTA record of each pixel of a row (the RTL's sm_wta): dw[x] the lowest level of least
// A(x, .), c1[x] = A(x, dw), c2[x] the least A(x, k) over |k - dw| >= 2 (c1 when there is
// none), cmax[x] the greatest A(x, .).
void wta_row(const uint8_t* agg, int w, int nd, uint8_t* dw, uint8_t* c1, uint8_t* c2, uint8_t* cmax);

// Band entry j (0..4) of a pixel's WTA record: A(x, dw - 2 + j) of its costs a[0..nd-1],
// 0 outside 0..nd-1.
inline uint8_t wta_band(const uint8_t* a, int nd, int dw, int j) {
  const int k = dw - 2 + j;
  return k >= 0 && k < nd ? a[k] : uint8_t{0};
}

// Right-view WTA of one line: out[xr] = the lowest k of least A(xr + k, k) over the levels
// with xr + k < w (a diagonal minimum the RTL keeps as one running (cost, level) per level).
void right_wta(const uint8_t* agg, int w, int nd, std::vector<uint8_t>& out);

// Gap of each unmatched run of one line: |the match right of it - the match left of it|,
// 255 when the run starts at x = 0 or ends at the line end; 0 for matched pixels.
void run_gaps(const std::vector<int>& match, uint8_t* out);

// Background fill of one line: for unmatched x, min(the match left of x, every match right
// of x) (one of them when the other does not exist, 0 when the line has no match); matched
// x keep their level. (The traceback runs right to left, so the running minimum is free.)
void fill_background(const std::vector<int>& match, uint8_t* out);

}  // namespace sm
