#include "dp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace sm {

namespace {
int clog2(uint64_t v) {  // ceil(log2(v)), as Verilog's $clog2
  int n = 0;
  while ((uint64_t{1} << n) < v) ++n;
  return n;
}
}  // namespace

int dp_acc_bits(const HwConfig& hw) {
  const uint64_t mw = static_cast<uint64_t>(hw.max_width);
  const uint64_t cmax = (uint64_t{1} << hw.cost_bits()) - 1;
  return clog2(mw * cmax + 2 * mw * 255 + 1) + 1;
}

void trellis_line(const uint8_t* agg, int n, uint8_t occ, const HwConfig& hw, DpScratch& s,
                  DpLine& out) {
  const int nd = hw.disp;
  const int acc_w = dp_acc_bits(hw);
  const uint32_t mask = (acc_w >= 32) ? 0xffffffffu : ((1u << acc_w) - 1);
  const uint32_t big = 1u << (acc_w - 1);
  const int sites = 2 * n;
  s.u0.assign(nd, big);
  s.u1.assign(nd, 0);
  s.dec.assign(static_cast<size_t>(sites + 1) * nd, 0);
  s.u0[0] = 0;

  // Forward pass, one site at a time (the hardware does two per clock).
  for (int i = 1; i <= sites; ++i) {
    const uint32_t* up = s.u0.data();
    uint32_t* uc = s.u1.data();
    uint8_t* dec = &s.dec[static_cast<size_t>(i) * nd];
    // matched nodes: i + d odd
    for (int d = (i & 1) ? 0 : 1; d < nd; d += 2) {
      const int xl = (i - 1 + d) / 2;
      const uint32_t a = (xl < n) ? agg[static_cast<size_t>(xl) * nd + d] : 0u;
      uc[d] = (up[d] + a) & mask;
    }
    // occlusion nodes: i + d even; first of choice 0, 1, 2 reaching the minimum
    for (int d = (i & 1) ? 1 : 0; d < nd; d += 2) {
      uint32_t best = up[d];
      uint8_t ch = 0;
      if (d >= 1) {
        const uint32_t c1 = (up[d - 1] + occ) & mask;
        if (c1 < best) best = c1, ch = 1;
      }
      if (d <= nd - 2) {
        const uint32_t c2 = (up[d + 1] + occ) & mask;
        if (c2 < best) best = c2, ch = 2;
      }
      uc[d] = best;
      dec[d] = ch;
    }
    std::swap(s.u0, s.u1);
  }
  out.end_cost = s.u0[0];

  // Backward pass from (2N, 0).
  out.path.assign(sites + 1, 0);
  out.match.assign(n, -1);
  int d = 0;
  for (int i = sites; i >= 1; --i) {
    out.path[i] = d;
    if ((i + d) & 1) {
      out.match[(i - 1 + d) / 2] = d;
    } else {
      const uint8_t ch = s.dec[static_cast<size_t>(i) * nd + d];
      d += (ch == 1) ? -1 : (ch == 2) ? 1 : 0;
    }
  }
  out.path[0] = d;
  dp_fill(out.match, out.disp);
}

void dp_fill(const std::vector<int>& match, std::vector<DispPix>& disp) {
  const int n = static_cast<int>(match.size());
  disp.assign(n, make_disp(0, true));
  int first = -1;
  for (int x = 0; x < n && first < 0; ++x)
    if (match[x] >= 0) first = x;
  if (first < 0) return;  // no match in the line: 0
  int fill = match[first];  // left of the first match: disp(first)
  int prev = -1;            // disparity of the match left of x, -1 before the first
  for (int x = 0; x < n; ++x) {
    if (match[x] >= 0) {
      if (prev >= 0)  // pixels since the previous match get min(disp(a), disp(b))
        for (int k = x - 1; k >= 0 && match[k] < 0; --k)
          disp[k] = make_disp(std::min(prev, match[x]), true);
      prev = match[x];
      disp[x] = make_disp(match[x], true);
    } else {
      disp[x] = make_disp(prev >= 0 ? prev : fill, true);  // right of the last: disp(last)
    }
  }
}

DispImage trellis_dp(const CostVolume& agg, uint8_t occ, const HwConfig& hw) {
  if (agg.d != hw.disp)
    throw std::invalid_argument(
        fmt::format("trellis_dp: cost volume has {} levels, DISP is {}", agg.d, hw.disp));
  if (agg.w > hw.max_width || agg.w < 1)
    throw std::invalid_argument(
        fmt::format("trellis_dp: width {} outside 1..MAX_WIDTH={}", agg.w, hw.max_width));
  DispImage out(agg.w, agg.h);
  DpScratch s;
  DpLine line;
  for (int y = 0; y < agg.h; ++y) {
    trellis_line(agg.pix(0, y), agg.w, occ, hw, s, line);
    std::copy(line.disp.begin(), line.disp.end(), &out.at(0, y));
  }
  return out;
}

}  // namespace sm
