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

// key[j]: the least (A << 8 | k) offered to right pixel xr = w - 1 - j, whose low byte is
// the lowest level of least cost (a 16-bit minimum instead of a compare and two selects);
// pixel x offers A(x, k) to right pixel x - k, i.e. to j = w - 1 - x + k, so one pixel's
// levels update a contiguous run of entries. Entries j >= w (right pixels left of the
// image, x < k) take offers and are ignored, so every pixel runs the same nd levels; key
// holds w + nd entries.
SM_HOT void right_wta_run(const uint8_t* agg, int w, int nd, uint16_t* __restrict key) {
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    uint16_t* __restrict c = key + (w - 1 - x);
    for (int i = 0; i < nd; ++i) {
      const auto offer = static_cast<uint16_t>(a[i] << 8 | i);
      c[i] = offer < c[i] ? offer : c[i];
    }
  }
}

// kNear[256 + j] = 255 for |j| <= 1, else 0: kNear + 256 - dw masks the levels near dw.
struct NearMask {
  uint8_t m[512] = {};
  NearMask() { m[255] = m[256] = m[257] = 255; }
};
const NearMask kNear;

}  // namespace

// The second pass ORs 255 into dw - 1 .. dw + 1 (a sliding mask), which cannot lower the
// least of the others.
SM_HOT void wta_row(const uint8_t* agg, int w, int nd, uint8_t* dw, uint8_t* c1, uint8_t* c2, uint8_t* cmax) {
  if (nd < 1) return;
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    uint8_t m = 255, hi = 0;
    for (int k = 0; k < nd; ++k) {
      m = a[k] < m ? a[k] : m;
      hi = a[k] > hi ? a[k] : hi;
    }
    const int best = static_cast<int>(static_cast<const uint8_t*>(std::memchr(a, m, static_cast<size_t>(nd))) - a);
    const uint8_t* near = kNear.m + 256 - best;
    uint8_t other = 255;
    for (int k = 0; k < nd; ++k) {
      const auto v = static_cast<uint8_t>(a[k] | near[k]);
      other = v < other ? v : other;
    }
    const bool any = best >= 2 || best + 2 < nd;
    dw[x] = static_cast<uint8_t>(best);
    c1[x] = m;
    c2[x] = any ? other : m;
    cmax[x] = hi;
  }
}

void right_wta(const uint8_t* agg, int w, int nd, std::vector<uint8_t>& out) {
  std::vector<uint16_t> key(static_cast<size_t>(w + nd), 0xffff);
  right_wta_run(agg, w, nd, key.data());
  out.resize(static_cast<size_t>(w));
  for (int xr = 0; xr < w; ++xr)
    out[static_cast<size_t>(xr)] = static_cast<uint8_t>(key[static_cast<size_t>(w - 1 - xr)]);
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
  uint8_t* const dw = &ev.dw.at(0, y);
  wta_row(agg, w, nd, dw, &ev.c1.at(0, y), &ev.c2.at(0, y), &ev.cmax.at(0, y));
  // Row pointers taken once: a byte store through one plane could alias another's.
  uint8_t *const d_out = &ev.d.at(0, y), *const matched = &ev.matched.at(0, y), *const lr = &ev.lr.at(0, y);
  uint8_t *const cm = &ev.cm.at(0, y), *const c0 = &ev.c0.at(0, y), *const cp = &ev.cp.at(0, y);
  uint8_t* band[5];
  for (size_t j = 0; j < 5; ++j) band[j] = &ev.band[j].at(0, y);
  const int* const match = line.match.data();
  const DispPix* const disp = line.disp.data();
  const uint8_t* const rwp = rw.data();
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    const int d = static_cast<int>(disp_value(disp[x]));
    auto at = [&](int k) { return k >= 0 && k < nd ? a[k] : uint8_t{0}; };
    d_out[x] = static_cast<uint8_t>(d);
    matched[x] = match[x] >= 0;
    cm[x] = at(d - 1);
    c0[x] = at(d);
    cp[x] = at(d + 1);
    lr[x] = x >= d ? rwp[x - d] : uint8_t{255};
    const int best = dw[x];
    for (int j = 0; j < 5; ++j) band[j][x] = wta_band(a, nd, best, j);
  }
}

Evidence evidence_frame(const CostVolume& agg, const Image8& left, uint8_t occ, uint8_t occ_edge, uint8_t edge_t,
                        const HwConfig& hw) {
  Evidence ev(agg.w, agg.h);
  DpScratch scratch;
  DpLine line;
  std::vector<uint8_t> pen;
  for (int y = 0; y < agg.h; ++y) {
    edge_penalties(&left.px[static_cast<size_t>(y) * left.w], agg.w, occ, occ_edge, edge_t, pen);
    const uint8_t* a = agg.pix(0, y);
    trellis_line_pen(a, agg.w, pen.data(), hw, scratch, line);
    evidence_line(a, agg.w, agg.d, line, y, ev);
  }
  return ev;
}

}  // namespace sm
