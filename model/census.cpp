#include "census.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace sm {

CensusImage census_transform(const Image8& in, const HwConfig& hw) {
  if (hw.census < 3 || hw.census > 15 || hw.census % 2 == 0)
    throw std::invalid_argument(
        fmt::format("census_transform: census {} must be odd, 3..15", hw.census));
  const int r = (hw.census - 1) / 2;
  const int w = in.w, h = in.h;
  CensusImage out(w, h, CensusVec{0, 0, 0, 0});
  // One neighbour offset at a time over the whole image: the inner loop is a plain
  // compare-and-or over a row, with the column range clipped instead of tested.
  int k = 0;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const int word = k >> 6;
      const uint64_t bit = uint64_t{1} << (k & 63);
      const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
      for (int y = std::max(0, -dy); y < std::min(h, h - dy); ++y) {
        const uint8_t* c = &in.px[static_cast<size_t>(y) * w];
        const uint8_t* n = &in.px[static_cast<size_t>(y + dy) * w + dx];
        CensusVec* o = &out.px[static_cast<size_t>(y) * w];
        for (int x = x0; x < x1; ++x)
          if (n[x] < c[x]) o[x][word] |= bit;
      }
      ++k;
    }
  }
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
  for (int y = 0; y < cl.h; ++y) {
    const CensusVec* l = &cl.px[static_cast<size_t>(y) * cl.w];
    const CensusVec* rr = &cr.px[static_cast<size_t>(y) * cr.w];
    for (int x = 0; x < cl.w; ++x) {
      uint8_t* o = out.pix(x, y);
      const int dmax = std::min(nd - 1, x);
      for (int d = 0; d <= dmax; ++d) o[d] = static_cast<uint8_t>(census_distance(l[x], rr[x - d]));
      for (int d = dmax + 1; d < nd; ++d) o[d] = cb;
    }
  }
  return out;
}

}  // namespace sm
