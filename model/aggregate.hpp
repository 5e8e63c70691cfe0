// Support-weight cost aggregation (docs/algorithm.md, section 5): model of
// rtl/sm_sw_aggregate.v.
#pragma once

#include <array>
#include <cstdint>

#include "sm_types.hpp"

namespace sm {

// RECIP(s) = floor((4096 + floor(s/2)) / s) for s >= 1, RECIP(0) = 0: the reciprocal
// of a weight sum in 1/4096 units, rounded to nearest (the hardware's ROM).
constexpr int kRecipShift = 12;
constexpr uint32_t sw_recip(uint32_t s) { return s == 0 ? 0u : ((1u << kRecipShift) + s / 2) / s; }

// Weight of a neighbour whose left-image intensity differs from the centre's by
// |dI|: code = table[min(|dI| >> 3, 31)], weight 0 for code 0 else 1 << (code - 1).
constexpr uint32_t sw_weight(const std::array<uint8_t, 32>& table, int abs_diff) {
  const int k = (abs_diff >> 3) < 31 ? (abs_diff >> 3) : 31;
  const uint32_t code = table[static_cast<size_t>(k)] & 3u;
  return code == 0 ? 0u : 1u << (code - 1);
}

// raw: Hamming costs (raw.d == hw.disp levels, values 0..CB); left: the left
// rectified image (same size), source of the weights; table: 2-bit weight codes by
// |dI| >> 3. Returns the CW-bit aggregated costs A(x, y, d). Throws
// std::invalid_argument when the sizes do not match or SW is not odd, 1..7.
// threads: rows computed in that many bands (same result for any count).
CostVolume sw_aggregate(const CostVolume& raw, const Image8& left, const std::array<uint8_t, 32>& table,
                        const HwConfig& hw, int threads = 1);

}  // namespace sm
