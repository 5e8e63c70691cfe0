// Census transform and Hamming matching cost (docs/algorithm.md, sections 3-4).
#pragma once

#include "sm_types.hpp"

namespace sm {

// Census vector of every pixel of `in` with a hw.census x hw.census window: bit k is
// I(neighbour k) < I(centre), neighbours in raster order with the centre skipped;
// a neighbour outside the image is the pixel at the nearest position inside (coordinates
// clamped to the image, row and column independently). Bits above hw.census_bits() are 0.
// threads: rows computed in that many bands (model/parallel.hpp; same result for any count).
CensusImage census_transform(const Image8& in, const HwConfig& hw, int threads = 1);

// H(x, y, d) = popcount(cl(x, y) ^ cr(x - d, y)) for d = 0..hw.disp-1, or
// hw.census_bits() when x - d < 0. Throws std::invalid_argument on a size mismatch.
CostVolume hamming_cost(const CensusImage& cl, const CensusImage& cr, const HwConfig& hw, int threads = 1);

// The cost's intensity term (sm_ad_term): min(|a - b| >> ad_shift, ad_max) (HwConfig's
// AD_SHIFT and AD_MAX), 0 when ad_max is 0 (census only).
inline int ad_term(int a, int b, int ad_shift, int ad_max) {
  const int t = (a > b ? a - b : b - a) >> ad_shift;
  return t < ad_max ? t : ad_max;
}

// The matching cost sm_cost outputs (docs/algorithm.md, section 4): C(x, y, d) =
// min(H(x, y, d) + (ad_term(left(x, y), right(x - d, y)) << hw.cost_shift), CB) with H of
// hamming_cost, or CB = hw.census_bits() when x - d < 0. left and right are the images the
// census vectors came from. Throws std::invalid_argument on a size mismatch.
CostVolume matching_cost(const CensusImage& cl, const CensusImage& cr, const Image8& left, const Image8& right,
                         const HwConfig& hw, int threads = 1);

// popcount(a ^ b) over the four words.
inline int census_distance(const CensusVec& a, const CensusVec& b) {
  return __builtin_popcountll(a[0] ^ b[0]) + __builtin_popcountll(a[1] ^ b[1]) + __builtin_popcountll(a[2] ^ b[2]) +
         __builtin_popcountll(a[3] ^ b[3]);
}

}  // namespace sm
