// Row kernels shared by the whole-frame stage functions (census_transform, matching_cost,
// sw_aggregate, trellis_dp) and by run_pipeline, which streams a frame through them one
// row at a time like the hardware does (a few rows of cost in a ring instead of whole
// cost volumes: the volumes are 10 MB each at the paper configuration, and allocating
// and first-touching them cost more than the arithmetic). Internal to the model: not
// part of its interface. Because both paths call the same kernels on the same rows,
// they give the same bits. docs/performance.md, "Model speed vs OpenCV".
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sm_types.hpp"

// Speed: on x86-64 with GCC the hot kernels are also compiled for AVX-512 (x86-64-v4) and
// AVX2 and picked at run time (target_clones; the AVX-512 clone made the model 3% faster,
// mostly the aggregation's weight masks). Integer arithmetic only, so every clone computes the same bits;
// the baseline clone is the portable definition. SM_VEC_BYTES is the vector width the
// kernels that depend on it are written for: 32 (AVX2) where that clone exists or the
// build targets AVX2, else 16, the baseline width (SSE2, NEON), which wider generic
// vectors would be emulated on.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SM_HOT __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#define SM_VEC_BYTES 32
#define SM_X86_DISPATCH 1  // also: hand-written AVX2 kernels chosen at run time
#else
#define SM_HOT
#if defined(__AVX2__)
#define SM_VEC_BYTES 32
#else
#define SM_VEC_BYTES 16
#endif
#endif

namespace sm::detail {

// Bytes kept readable after every cost row handed to agg_row: the level loop reads whole
// 32-byte blocks, 64-byte ones in the AVX-512 variant (the lanes beyond the last level are
// computed and dropped).
constexpr size_t kCostPad = 64;

// An image with a border of r pixels on every side that repeats the nearest edge pixel
// (and room for whole vectors of pixels on the right): a neighbour outside the image
// then compares as the pixel at the clamped coordinates, without a test.
struct CensusPad {
  int w, h, r;
  size_t stride;
  std::vector<uint8_t> px;
  CensusPad(const Image8& in, int r);
  const uint8_t* row(int y) const { return px.data() + static_cast<size_t>(y + r) * stride + r; }
};

// Census vectors of row y (window side 2r+1); `out` has w entries.
void census_row(const CensusPad& in, int y, CensusVec* out);

// Hamming costs of one row: out[x * nd + d] = H >> shift with H = popcount(l[x] ^
// rr[x - d]) as an 8-bit value, or cb >> shift when x < d (shift 0: hamming_cost; the
// pipeline passes COST_SHIFT and gets C directly).
void cost_row(const CensusVec* l, const CensusVec* rr, int w, int nd, uint8_t cb, int shift, uint8_t* out);

// Adds the intensity terms to one row of costs (sm_cost_addsat): out[x * nd + d] =
// min(out + (ad_term(l[x], r[x - d]) << shift), cap) for x - d >= 0; the levels with x - d
// < 0 keep their value. On H (shift COST_SHIFT, cap CB) or on C = H >> COST_SHIFT (shift 0,
// cap CB >> COST_SHIFT): min(H + (t << s), CB) >> s = min((H >> s) + t, CB >> s), so both
// give the same C.
void add_term_row(const uint8_t* l, const uint8_t* r, int w, int nd, const HwConfig& hw, int shift, int cap,
                  uint8_t* out);

// Support-weight aggregation of row y (SW <= 7). c_rows[j + r] is row y + j of C = H >>
// COST_SHIFT (w * nd bytes followed by kCostPad readable bytes), j = -r..r; rows outside
// the image are never read (their weight is 0) and may be null. left: the left
// rectified image.
struct AggRow {
  int w, h, nd, r;
  uint32_t out_max;                        // 2^CW - 1
  int group;                               // neighbours whose C sum in one byte without wrapping
  std::array<uint8_t, 256> code;           // weight code by |dI| (0: weight 0, c: weight 1 << (c-1))
  std::array<uint16_t, 4 * 49 + 1> recip;  // sw_recip by weight sum (the ROM; no division per pixel)
  AggRow(int w_, int h_, int nd_, int sw, const std::array<uint8_t, 32>& table, const HwConfig& hw);
};
void agg_row(const AggRow& a, const uint8_t* const* c_rows, const uint8_t* left, int y, uint8_t* out);

}  // namespace sm::detail
