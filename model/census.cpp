#include "census.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

// Speed (docs/performance.md): the hot loops are written so the compiler vectorizes
// them, and on x86-64 with GCC each is also compiled for AVX2 (with POPCNT) and picked
// at run time (target_clones). Integer arithmetic only, so every clone computes the
// same bits; the baseline clone is the portable definition.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SM_HOT __attribute__((target_clones("avx2", "default")))
#else
#define SM_HOT
#endif

namespace sm {

namespace {

// Census bits in word-major bit planes (plane[word][y * w + x]): one neighbour offset
// at a time over the whole image, the inner loop a contiguous compare-shift-or that
// vectorizes; the column range is clipped instead of tested.
SM_HOT void census_planes(const uint8_t* in, int w, int h, int r, uint64_t* planes) {
  const size_t wh = static_cast<size_t>(w) * h;
  int k = 0;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (dx == 0 && dy == 0) continue;
      uint64_t* plane = planes + static_cast<size_t>(k >> 6) * wh;
      const int sh = k & 63;
      const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
      for (int y = std::max(0, -dy); y < std::min(h, h - dy); ++y) {
        const uint8_t* __restrict c = in + static_cast<size_t>(y) * w;
        const uint8_t* __restrict n = in + static_cast<size_t>(y + dy) * w + dx;
        uint64_t* __restrict o = plane + static_cast<size_t>(y) * w;
        for (int x = x0; x < x1; ++x) o[x] |= static_cast<uint64_t>(n[x] < c[x]) << sh;
      }
      ++k;
    }
  }
}

// One row of Hamming costs (all four words: exact for any input vector).
inline void cost_row(const CensusVec* l, const CensusVec* rr, int w, int nd, uint8_t cb,
                     uint8_t* out) {
  for (int x = 0; x < w; ++x) {
    uint8_t* o = out + static_cast<size_t>(x) * nd;
    const CensusVec a = l[x];
    const int dmax = std::min(nd - 1, x);
    for (int d = 0; d <= dmax; ++d) {
      const CensusVec& b = rr[x - d];
      int s = 0;
      for (int i = 0; i < 4; ++i) s += __builtin_popcountll(a[i] ^ b[i]);
      o[d] = static_cast<uint8_t>(s);
    }
    for (int d = dmax + 1; d < nd; ++d) o[d] = cb;
  }
}

SM_HOT void cost_rows(const CensusImage& cl, const CensusImage& cr, int nd, uint8_t cb,
                      uint8_t* out) {
  const int w = cl.w;
  for (int y = 0; y < cl.h; ++y) {
    const CensusVec* l = &cl.px[static_cast<size_t>(y) * w];
    const CensusVec* rr = &cr.px[static_cast<size_t>(y) * w];
    uint8_t* o = out + static_cast<size_t>(y) * w * nd;
    cost_row(l, rr, w, nd, cb, o);
  }
}

}  // namespace

CensusImage census_transform(const Image8& in, const HwConfig& hw) {
  if (hw.census < 3 || hw.census > 15 || hw.census % 2 == 0)
    throw std::invalid_argument(
        fmt::format("census_transform: census {} must be odd, 3..15", hw.census));
  const int r = (hw.census - 1) / 2;
  const int w = in.w, h = in.h;
  const size_t wh = static_cast<size_t>(w) * h;
  std::vector<uint64_t> planes(4 * wh, 0);
  census_planes(in.px.data(), w, h, r, planes.data());
  CensusImage out(w, h, CensusVec{0, 0, 0, 0});
  for (size_t i = 0; i < wh; ++i)
    out.px[i] = CensusVec{planes[i], planes[wh + i], planes[2 * wh + i], planes[3 * wh + i]};
  return out;
}

CostVolume hamming_cost(const CensusImage& cl, const CensusImage& cr, const HwConfig& hw) {
  if (cl.w != cr.w || cl.h != cr.h)
    throw std::invalid_argument(
        fmt::format("hamming_cost: left {}x{} and right {}x{} differ", cl.w, cl.h, cr.w, cr.h));
  if (hw.disp < 1 || hw.disp > 256)
    throw std::invalid_argument(fmt::format("hamming_cost: disp {} outside 1..256", hw.disp));
  const int nd = hw.disp;
  const auto cb = static_cast<uint8_t>(hw.census_bits());
  CostVolume out(cl.w, cl.h, nd);
  cost_rows(cl, cr, nd, cb, out.v.data());
  return out;
}

}  // namespace sm
