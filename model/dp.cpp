#include "dp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

// Speed (docs/performance.md): on x86-64 with GCC the forward pass is also compiled for
// AVX2 and picked at run time (target_clones); integer arithmetic only, same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SM_HOT __attribute__((target_clones("avx2", "default")))
#else
#define SM_HOT
#endif

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

SM_HOT void trellis_line(const uint8_t* agg, int n, uint8_t occ, const HwConfig& hw, DpScratch& s,
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
    // matched nodes: i + d odd; their left pixel xl = (i - 1 + d) / 2 is inside the
    // line for d < 2n - i + 1 (beyond it the cost is 0). Branch-free loops: speed only.
    const int dm0 = (i & 1) ? 0 : 1;
    const int dlim = std::min(nd, sites - i + 1);
    int d = dm0;
    for (; d < dlim; d += 2) {
      const int xl = (i - 1 + d) / 2;
      uc[d] = (up[d] + agg[static_cast<size_t>(xl) * nd + d]) & mask;
    }
    for (; d < nd; d += 2) uc[d] = up[d] & mask;
    // occlusion nodes: i + d even; first of choice 0, 1, 2 reaching the minimum. The
    // edge levels (no d - 1 / no d + 1) are peeled so the inner loop has no branches.
    const int do0 = (i & 1) ? 1 : 0;
    auto occ_node = [&](int dd, bool has_lo, bool has_hi) {
      uint32_t best = up[dd];
      uint8_t ch = 0;
      if (has_lo) {
        const uint32_t c1 = (up[dd - 1] + occ) & mask;
        if (c1 < best) best = c1, ch = 1;
      }
      if (has_hi) {
        const uint32_t c2 = (up[dd + 1] + occ) & mask;
        if (c2 < best) best = c2, ch = 2;
      }
      uc[dd] = best;
      dec[dd] = ch;
    };
    d = do0;
    if (d == 0 && d < nd) {
      occ_node(0, false, nd >= 2);
      d = 2;
    }
    for (; d <= nd - 2; d += 2) {
      const uint32_t b0 = up[d];
      const uint32_t c1 = (up[d - 1] + occ) & mask;
      const uint32_t c2 = (up[d + 1] + occ) & mask;
      const bool t1 = c1 < b0;
      const uint32_t b1 = t1 ? c1 : b0;
      const bool t2 = c2 < b1;
      uc[d] = t2 ? c2 : b1;
      dec[d] = static_cast<uint8_t>(t2 ? 2 : (t1 ? 1 : 0));
    }
    if (d == nd - 1 && d >= 1) occ_node(d, true, false);
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
