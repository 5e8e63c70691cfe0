#include "evidence.hpp"

#include <algorithm>
#include <cstdlib>

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

void right_wta(const uint8_t* agg, int w, int nd, std::vector<uint8_t>& out) {
  out.assign(static_cast<size_t>(w), 0);
  for (int xr = 0; xr < w; ++xr) {
    int best = 0;
    for (int k = 1; k < nd && xr + k < w; ++k)
      if (agg[static_cast<size_t>(xr + k) * nd + k] < agg[static_cast<size_t>(xr + best) * nd + best]) best = k;
    out[static_cast<size_t>(xr)] = static_cast<uint8_t>(best);
  }
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
    int best = 0, hi = a[0];
    for (int k = 1; k < nd; ++k) {
      if (a[k] < a[best]) best = k;
      hi = std::max<int>(hi, a[k]);
    }
    int second = -1;
    for (int k = 0; k < nd; ++k)
      if ((k < best - 1 || k > best + 1) && (second < 0 || a[k] < second)) second = a[k];
    ev.dw.at(x, y) = static_cast<uint8_t>(best);
    ev.c1.at(x, y) = a[best];
    ev.c2.at(x, y) = static_cast<uint8_t>(second < 0 ? a[best] : second);
    ev.cmax.at(x, y) = static_cast<uint8_t>(hi);
    for (int j = 0; j < 5; ++j) ev.band[static_cast<size_t>(j)].at(x, y) = at(best - 2 + j);
  }
}

}  // namespace sm
