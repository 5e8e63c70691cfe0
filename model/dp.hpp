// Trellis dynamic programming (docs/algorithm.md, section 6): the bit-exact model of
// sm_dp. One line at a time, on the centre-referenced grid of sites i = xl + xr.
#pragma once

#include <cstdint>
#include <vector>

#include "sm_types.hpp"

namespace sm {

// ACC_W = clog2(MAX_WIDTH*(2^CW - 1) + 2*MAX_WIDTH*255 + 1) + 1, BIG = 2^(ACC_W-1).
int dp_acc_bits(const HwConfig& hw);

// Everything the trellis of one line produces, for tests and tools.
struct DpLine {
  uint32_t end_cost = 0;      // U(2N, 0): cost of the optimal path
  std::vector<int> path;      // level of the traced path at every site 0..2N
  std::vector<int> match;     // disp(xl) of matched pixels, -1 when left-occluded
  std::vector<DispPix> disp;  // after the left-occlusion fill (valid bit set)
};

// Reusable work buffers of trellis_line, so a frame allocates once. Levels are kept
// split by parity (even d = 2m, odd d = 2m + 1), so that every loop of the forward pass
// runs over consecutive entries; S = ceil(DISP/2) rounded up to a multiple of 16.
struct DpScratch {
  std::vector<uint32_t> u0, u1;  // U of the even / odd levels at the current site
  std::vector<uint8_t> dec;      // choice of occlusion node (i, d) at i * S + d / 2,
                                 // (2N+1) * S entries (0, 1, 2; the vector pass writes 3 for 2)
  std::vector<uint16_t> cm;      // matched costs in site order, (N+1) * S pairs (dp.cpp)
  std::vector<uint32_t> pen;     // per-pixel penalties, padded, 32 bits (trellis_line_pen)
  std::vector<uint16_t> pt;      // the costs' pairs by level pair, then pixel (dp.cpp, AVX-512 gather)
};

// One line: agg[x * disp + d] = A(x, d) for x = 0..n-1 (CW-bit aggregated costs), n <=
// hw.max_width. Matched nodes with xl >= n use cost 0 (the hardware sees the next
// line there; such nodes never reach the end node, see algorithm.md).
void trellis_line(const uint8_t* agg, int n, uint8_t occ, const HwConfig& hw, DpScratch& s, DpLine& out);

// trellis_line with a penalty per left pixel instead of one occ (issue 21 study, not in the
// RTL): the occlusion node (i, d) (i + d even) costs pen[(i + d) / 2] on both of its diagonal
// choices; pen has n + 1 entries (xl = 0..n; nodes with xl > n never reach the end node).
// pen[x] == occ for every x gives trellis_line(agg, n, occ, ...) bit for bit.
void trellis_line_pen(const uint8_t* agg, int n, const uint8_t* pen, const HwConfig& hw, DpScratch& s, DpLine& out);

// Edge-dependent penalties of one line of the left image (docs/evaluation.md, "Edge-dependent
// occlusion penalty"): pen[x] = occ_edge where 1 <= x < n and |left[x] - left[x-1]| > edge_t,
// else occ (n + 1 entries).
void edge_penalties(const uint8_t* left, int n, uint8_t occ, uint8_t occ_edge, uint8_t edge_t,
                    std::vector<uint8_t>& pen);

// Left-occlusion fill of one line (match[x] = -1 for unmatched pixels), valid bit set.
void dp_fill(const std::vector<int>& match, std::vector<DispPix>& disp);

// The whole stage: every line of the aggregated cost volume (agg.d == hw.disp) with
// one occlusion penalty. Throws std::invalid_argument on a size mismatch.
// threads: lines computed in that many bands (same result for any count).
DispImage trellis_dp(const CostVolume& agg, uint8_t occ, const HwConfig& hw, int threads = 1);
// Every line with the edge-dependent penalties of the left image's row (left: the image the
// weights came from, agg.w x agg.h).
DispImage trellis_dp_edge(const CostVolume& agg, const Image8& left, uint8_t occ, uint8_t occ_edge, uint8_t edge_t,
                          const HwConfig& hw, int threads = 1);

}  // namespace sm
