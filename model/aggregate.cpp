#include "aggregate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

// Speed (docs/performance.md): on x86-64 with GCC the function is also compiled for AVX2
// and picked at run time (target_clones); integer arithmetic only, so both clones give
// the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SM_HOT __attribute__((target_clones("avx2", "default")))
#else
#define SM_HOT
#endif

namespace sm {

namespace {

struct AggArgs {
  const uint8_t* c;     // C = H >> COST_SHIFT, w x h x nd
  const uint8_t* left;  // w x h
  const std::array<uint8_t, 32>* table;
  int w, h, nd, r;
  uint32_t out_max, half;
  uint8_t* out;
};

#if defined(__GNUC__)
// 16 levels per vector: the accumulators of up to 128 levels stay in registers while the
// pixel's neighbours are summed (GCC/Clang vector extensions; 16-bit lanes wrap exactly
// like the reference's uint16_t sums).
typedef uint16_t V16 __attribute__((vector_size(32)));
typedef uint8_t V8 __attribute__((vector_size(16)));

template <int NV>
inline void agg_levels(const size_t* nb_off, const uint16_t* nb_w, int cnt, int d0, uint32_t rec,
                       const AggArgs& a, uint8_t* o) {
  V16 acc[NV] = {};
  for (int k = 0; k < cnt; ++k) {
    const uint8_t* cq = a.c + nb_off[k] + d0;
    const V16 wv = V16{} + nb_w[k];
    for (int v = 0; v < NV; ++v) {
      V8 b;
      std::memcpy(&b, cq + 16 * v, sizeof b);
      acc[v] += __builtin_convertvector(b, V16) * wv;
    }
  }
  uint16_t t[16 * NV];
  std::memcpy(t, acc, sizeof t);
  for (int d = 0; d < 16 * NV; ++d) {
    const uint32_t v = (t[d] * rec + a.half) >> kRecipShift;
    o[d0 + d] = static_cast<uint8_t>(std::min(v, a.out_max));
  }
}
constexpr bool kVecLevels = true;
#else
constexpr bool kVecLevels = false;
#endif

SM_HOT void agg_image(const AggArgs& a) {
  const int w = a.w, h = a.h, r = a.r, nd = a.nd;
  const int nmax = (2 * r + 1) * (2 * r + 1);
  std::vector<size_t> nb_off(static_cast<size_t>(nmax));
  std::vector<uint16_t> nb_w(static_cast<size_t>(nmax));
  std::vector<uint16_t> acc_v(static_cast<size_t>(nd));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int p = a.left[static_cast<size_t>(y) * w + x];
      // The window's neighbours with a non-zero weight.
      int cnt = 0;
      uint32_t wsum = 0;
      for (int j = std::max(-r, -y); j <= std::min(r, h - 1 - y); ++j) {
        const uint8_t* lrow = a.left + static_cast<size_t>(y + j) * w;
        for (int i = std::max(-r, -x); i <= std::min(r, w - 1 - x); ++i) {
          const uint32_t wq = sw_weight(*a.table, std::abs(lrow[x + i] - p));
          if (wq == 0) continue;
          wsum += wq;
          nb_w[cnt] = static_cast<uint16_t>(wq);
          nb_off[cnt++] = (static_cast<size_t>(y + j) * w + (x + i)) * nd;
        }
      }
      const uint32_t rec = sw_recip(wsum);
      uint8_t* __restrict o = a.out + (static_cast<size_t>(y) * w + x) * nd;
#if defined(__GNUC__)
      if (kVecLevels && nd % 16 == 0) {
        const size_t* off = nb_off.data();
        const uint16_t* wt = nb_w.data();
        int d0 = 0;  // widest blocks first; each block of levels is independent
        for (; d0 + 128 <= nd; d0 += 128) agg_levels<8>(off, wt, cnt, d0, rec, a, o);
        for (; d0 + 64 <= nd; d0 += 64) agg_levels<4>(off, wt, cnt, d0, rec, a, o);
        for (; d0 + 32 <= nd; d0 += 32) agg_levels<2>(off, wt, cnt, d0, rec, a, o);
        for (; d0 < nd; d0 += 16) agg_levels<1>(off, wt, cnt, d0, rec, a, o);
        continue;
      }
#endif
      uint16_t* __restrict acc = acc_v.data();
      for (int d = 0; d < nd; ++d) acc[d] = 0;
      for (int k = 0; k < cnt; ++k) {
        const uint8_t* __restrict cq = a.c + nb_off[k];
        const uint16_t wm = nb_w[k];
        for (int d = 0; d < nd; ++d) acc[d] = static_cast<uint16_t>(acc[d] + cq[d] * wm);
      }
      for (int d = 0; d < nd; ++d) {
        const uint32_t v = (acc[d] * rec + a.half) >> kRecipShift;
        o[d] = static_cast<uint8_t>(std::min(v, a.out_max));
      }
    }
  }
}

}  // namespace

SM_HOT CostVolume sw_aggregate(const CostVolume& raw, const Image8& left,
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
  const AggArgs a{c.data(), left.px.data(), &table, w, h, nd, r, out_max, half, out.v.data()};
  agg_image(a);
  return out;
}

}  // namespace sm
