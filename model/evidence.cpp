#include "evidence.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "kernels.hpp"

namespace sm {

Evidence::Evidence(int w, int h)
    : d(w, h),
      matched(w, h),
      gap(w, h),
      fill_bg(w, h),
      cm(w, h),
      c0(w, h),
      cp(w, h),
      dw(w, h),
      c1(w, h),
      c2(w, h),
      cmax(w, h),
      lr(w, h) {
  for (auto& b : band) b = Image8(w, h);
}

void fill_background(const std::vector<int>& match, uint8_t* out) {
  const int n = static_cast<int>(match.size());
  std::vector<int> right(static_cast<size_t>(n));  // least match right of x (-1: none)
  for (int x = n - 1, rmin = -1; x >= 0; --x) {
    right[static_cast<size_t>(x)] = rmin;
    const int m = match[static_cast<size_t>(x)];
    if (m >= 0 && (rmin < 0 || m < rmin)) rmin = m;
  }
  int left = -1;  // the match left of x (-1: none)
  for (int x = 0; x < n; ++x) {
    const int m = match[static_cast<size_t>(x)], r = right[static_cast<size_t>(x)];
    if (m >= 0) left = m;
    const int f = m >= 0 ? m : left < 0 ? r : r < 0 ? left : std::min(left, r);
    out[x] = static_cast<uint8_t>(f < 0 ? 0 : f);
  }
}

namespace {

// The level loops below are plain loops over bytes that GCC vectorises (min/max
// reductions, element-wise selects); SM_HOT also compiles them for AVX2, picked at run
// time. Integer only, so every clone gives the same bits.

// The least of p[0..n) (255 when n <= 0).
inline uint8_t least(const uint8_t* p, int n) {
  uint8_t m = 255;
  for (int i = 0; i < n; ++i) m = p[i] < m ? p[i] : m;
  return m;
}

// The greatest of p[0..n) (n >= 1).
inline uint8_t greatest(const uint8_t* p, int n) {
  uint8_t m = 0;
  for (int i = 0; i < n; ++i) m = p[i] > m ? p[i] : m;
  return m;
}

// bc[j] / bk[j]: the running (cost, level) of right pixel xr = w - 1 - j; pixel x offers
// A(x, k) to right pixel x - k, i.e. to j = w - 1 - x + k, so one pixel's levels update a
// contiguous run of entries (strictly less: the lowest level wins, as levels rise with x).
SM_HOT void right_wta_run(const uint8_t* agg, int w, int nd, uint8_t* __restrict bc, uint8_t* __restrict bk) {
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    uint8_t* __restrict c = bc + (w - 1 - x);
    uint8_t* __restrict k = bk + (w - 1 - x);
    const int n = std::min(nd, x + 1);
    for (int i = 0; i < n; ++i) {
      const bool lt = a[i] < c[i];
      k[i] = lt ? static_cast<uint8_t>(i) : k[i];
      c[i] = lt ? a[i] : c[i];
    }
  }
}

// Per pixel of a row: dw (first level of least cost), c1, c2 (least cost over the levels
// at least 2 from dw, c1 when there is none) and cmax.
SM_HOT void wta_row(const uint8_t* agg, int w, int nd, uint8_t* dw, uint8_t* c1, uint8_t* c2, uint8_t* cmax) {
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    const uint8_t m = least(a, nd);
    const int best = static_cast<int>(static_cast<const uint8_t*>(std::memchr(a, m, static_cast<size_t>(nd))) - a);
    const bool any = best >= 2 || best + 2 < nd;
    const uint8_t below = least(a, best - 1), above = best + 2 < nd ? least(a + best + 2, nd - best - 2) : 255;
    dw[x] = static_cast<uint8_t>(best);
    c1[x] = m;
    c2[x] = any ? std::min(below, above) : m;
    cmax[x] = greatest(a, nd);
  }
}

}  // namespace

void right_wta(const uint8_t* agg, int w, int nd, std::vector<uint8_t>& out) {
  std::vector<uint8_t> bc(static_cast<size_t>(w), 255), bk(static_cast<size_t>(w), 0);
  right_wta_run(agg, w, nd, bc.data(), bk.data());
  out.resize(static_cast<size_t>(w));
  for (int xr = 0; xr < w; ++xr) out[static_cast<size_t>(xr)] = bk[static_cast<size_t>(w - 1 - xr)];
}

void run_gaps(const std::vector<int>& match, uint8_t* out) {
  const int n = static_cast<int>(match.size());
  int left = -1;
  for (int x = 0; x < n;) {
    if (match[static_cast<size_t>(x)] >= 0) {
      left = match[static_cast<size_t>(x)];
      out[x++] = 0;
      continue;
    }
    int e = x;
    while (e < n && match[static_cast<size_t>(e)] < 0) ++e;
    const int g = (left < 0 || e == n) ? 255 : std::min(254, std::abs(match[static_cast<size_t>(e)] - left));
    for (; x < e; ++x) out[x] = static_cast<uint8_t>(g);
  }
}

void evidence_line(const uint8_t* agg, int w, int nd, const DpLine& line, int y, Evidence& ev) {
  fill_background(line.match, &ev.fill_bg.at(0, y));
  run_gaps(line.match, &ev.gap.at(0, y));
  std::vector<uint8_t> rw;
  right_wta(agg, w, nd, rw);
  wta_row(agg, w, nd, &ev.dw.at(0, y), &ev.c1.at(0, y), &ev.c2.at(0, y), &ev.cmax.at(0, y));
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    const int d = static_cast<int>(disp_value(line.disp[static_cast<size_t>(x)]));
    auto at = [&](int k) { return k >= 0 && k < nd ? a[k] : uint8_t{0}; };
    ev.d.at(x, y) = static_cast<uint8_t>(d);
    ev.matched.at(x, y) = line.match[static_cast<size_t>(x)] >= 0;
    ev.cm.at(x, y) = at(d - 1);
    ev.c0.at(x, y) = at(d);
    ev.cp.at(x, y) = at(d + 1);
    ev.lr.at(x, y) = x >= d ? rw[static_cast<size_t>(x - d)] : uint8_t{255};
    const int best = ev.dw.at(x, y);
    for (int j = 0; j < 5; ++j) ev.band[static_cast<size_t>(j)].at(x, y) = at(best - 2 + j);
  }
}

}  // namespace sm
