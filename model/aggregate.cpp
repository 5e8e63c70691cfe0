#include "aggregate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace sm {

CostVolume sw_aggregate(const CostVolume& raw, const Image8& left,
                        const std::array<uint8_t, 32>& table, const HwConfig& hw) {
  if (raw.w != left.w || raw.h != left.h)
    throw std::invalid_argument(fmt::format("sw_aggregate: cost volume {}x{} but left image {}x{}",
                                            raw.w, raw.h, left.w, left.h));
  if (raw.d != hw.disp)
    throw std::invalid_argument(
        fmt::format("sw_aggregate: cost volume has {} levels, DISP is {}", raw.d, hw.disp));
  if (hw.sw < 1 || hw.sw % 2 == 0)
    throw std::invalid_argument(fmt::format("sw_aggregate: SW {} must be odd", hw.sw));

  const int w = raw.w, h = raw.h, nd = raw.d, r = (hw.sw - 1) / 2;
  const uint32_t out_max = (1u << hw.cost_bits()) - 1;
  const uint32_t half = 1u << (kRecipShift - 1);

  // C = H >> COST_SHIFT once for the whole volume; the inner loops then only shift by
  // the weight's exponent. The largest sum, 4*SW*SW*CMAX (43904 at SW 7, CENSUS 15,
  // COST_SHIFT 0), fits 16 bits, which keeps the level loop narrow and vectorizable.
  std::vector<uint8_t> c(raw.v.size());
  for (size_t i = 0; i < c.size(); ++i) c[i] = static_cast<uint8_t>(raw.v[i] >> hw.cost_shift);

  CostVolume out(w, h, nd);
  std::vector<uint16_t> acc(static_cast<size_t>(nd));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = left.at(x, y);
      std::fill(acc.begin(), acc.end(), uint16_t{0});
      uint32_t wsum = 0;
      for (int j = std::max(-r, -y); j <= std::min(r, h - 1 - y); ++j) {
        for (int i = std::max(-r, -x); i <= std::min(r, w - 1 - x); ++i) {
          const uint32_t wq = sw_weight(table, std::abs(left.at(x + i, y + j) - p));
          if (wq == 0) continue;
          wsum += wq;
          const uint16_t wm = static_cast<uint16_t>(wq);
          const uint8_t* __restrict cq = &c[(static_cast<size_t>(y + j) * w + (x + i)) * nd];
          uint16_t* __restrict a = acc.data();
          for (int d = 0; d < nd; ++d) a[d] = static_cast<uint16_t>(a[d] + cq[d] * wm);
        }
      }
      const uint32_t rec = sw_recip(wsum);
      uint8_t* o = out.pix(x, y);
      for (int d = 0; d < nd; ++d) {
        const uint32_t v = (acc[d] * rec + half) >> kRecipShift;
        o[d] = static_cast<uint8_t>(std::min(v, out_max));
      }
    }
  }
  return out;
}

}  // namespace sm
