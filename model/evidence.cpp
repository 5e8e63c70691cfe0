#include "evidence.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "kernels.hpp"

#if defined(SM_X86_DISPATCH)
#include <immintrin.h>
#endif

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

#if defined(SM_X86_DISPATCH)
// right_wta_run with AVX-512 (BW, VBMI; chosen at run time where the CPU has them and
// SM_NO_AVX512 is not set): the nd entries pixel x offers to, key[w-1-x ..], are kept in
// registers (32 levels each, NB <= 8) and shift up by one entry per pixel, so no entry is
// stored and reloaded while it still takes offers (in the memory form each pixel's loads
// wait for the previous pixel's overlapping stores). The entry leaving the top, w-1-x+nd-1,
// has had all its offers and is stored. Offers are A << 8 | k, built by one byte permute
// per 32 levels; the same 16-bit minima, so the same bits.
#define SM_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512vbmi")))
template <int NB>
SM_AVX512 void right_wta_regs(const uint8_t* agg, int w, int nd, uint16_t* key) {
  __m512i win[NB], level[NB], spread[2];
  __mmask64 load_mask[(NB + 1) / 2];
  __mmask32 live[NB];
  alignas(64) uint16_t lv[32];
  alignas(64) uint8_t sp[2][64];
  for (int k = 0; k < 64; ++k) {  // byte 2k+1 of spread[h] <- level byte 32h + k
    sp[0][k] = static_cast<uint8_t>(k / 2);
    sp[1][k] = static_cast<uint8_t>(32 + k / 2);
  }
  spread[0] = _mm512_load_si512(sp[0]);
  spread[1] = _mm512_load_si512(sp[1]);
  for (int b = 0; b < NB; ++b) {
    for (int k = 0; k < 32; ++k) lv[k] = static_cast<uint16_t>(32 * b + k);
    level[b] = _mm512_load_si512(lv);
    win[b] = _mm512_set1_epi16(-1);
    const int n = std::clamp(nd - 32 * b, 0, 32);
    live[b] = n == 32 ? ~__mmask32{0} : (__mmask32{1} << n) - 1;
  }
  for (int h = 0; h < (NB + 1) / 2; ++h) {
    const int n = std::clamp(nd - 64 * h, 0, 64);
    load_mask[h] = n == 64 ? ~__mmask64{0} : (__mmask64{1} << n) - 1;
  }
  alignas(64) uint16_t ix[32];  // entry k <- entry k - 1 of the same register, entry 0 <- entry 31 of the one below
  ix[0] = 31;
  for (int k = 1; k < 32; ++k) ix[k] = static_cast<uint16_t>(32 + k - 1);
  const __m512i up_one = _mm512_load_si512(ix);
  const int top_b = (nd - 1) / 32, top_lane = (nd - 1) % 32;
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    for (int h = 0; h < (NB + 1) / 2; ++h) {
      const __m512i bytes = _mm512_maskz_loadu_epi8(load_mask[h], a + 64 * h);
      for (int v = 0; v < 2 && 2 * h + v < NB; ++v) {
        const int b = 2 * h + v;
        const __m512i offer = _mm512_mask_permutexvar_epi8(level[b], 0xaaaaaaaaaaaaaaaaull, spread[v], bytes);
        win[b] = _mm512_mask_min_epu16(win[b], live[b], win[b], offer);
      }
    }
    // Entry nd - 1 (key index w-1-x+nd-1) is complete.
    uint16_t* base = key + (w - 1 - x) + 32 * top_b;
    _mm512_mask_storeu_epi16(base, __mmask32{1} << top_lane, win[top_b]);
    if (x == w - 1) break;  // the window holds key[0 ..] now
    for (int b = NB - 1; b > 0; --b) win[b] = _mm512_permutex2var_epi16(win[b - 1], up_one, win[b]);
    win[0] = _mm512_mask_mov_epi16(_mm512_permutex2var_epi16(win[0], up_one, win[0]), 1, _mm512_set1_epi16(-1));
  }
  for (int b = 0; b < NB; ++b) _mm512_mask_storeu_epi16(key + 32 * b, live[b], win[b]);
}
#undef SM_AVX512
#endif

// kNear[256 + j] = 255 for |j| <= 1, else 0: kNear + 256 - dw masks the levels near dw.
struct NearMask {
  uint8_t m[512] = {};
  NearMask() { m[255] = m[256] = m[257] = 255; }
};
const NearMask kNear;

#if defined(SM_X86_DISPATCH)
bool wta_avx512(const uint8_t* agg, int w, int nd, uint8_t* dw, uint8_t* c1, uint8_t* c2, uint8_t* cmax);
#endif

}  // namespace

// The second pass ORs 255 into dw - 1 .. dw + 1 (a sliding mask), which cannot lower the
// least of the others.
SM_HOT void wta_row(const uint8_t* agg, int w, int nd, uint8_t* dw, uint8_t* c1, uint8_t* c2, uint8_t* cmax) {
  if (nd < 1) return;
#if defined(SM_X86_DISPATCH)
  if (wta_avx512(agg, w, nd, dw, c1, c2, cmax)) return;
#endif
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

namespace {

#if defined(SM_X86_DISPATCH)
// wta_row with AVX-512 (chosen as right_wta_regs is): a pixel's levels in NC registers of
// 64 (the lanes past the last level hold 255 for the minima, 0 for the maximum), the
// least, greatest and second least cost as byte minima reduced to one value, the WTA level
// the first lane equal to the least. Same bits as the loops.
#define SM_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl")))
// The least byte of v.
SM_AVX512 inline uint8_t least_byte(__m512i v) {
  // (Zero-masked extracts with every lane kept: the plain ones start from an undefined
  // vector that GCC 12 warns about.)
  const __m256i y =
      _mm256_min_epu8(_mm512_maskz_extracti64x4_epi64(0xff, v, 0), _mm512_maskz_extracti64x4_epi64(0xff, v, 1));
  __m128i x = _mm_min_epu8(_mm256_castsi256_si128(y), _mm256_extracti128_si256(y, 1));
  x = _mm_min_epu8(x, _mm_srli_epi16(x, 8));  // byte pairs: the least in the low byte, 0 above
  return static_cast<uint8_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(x)));
}
// Bits lo .. lo + 2 of a 64-bit mask (the part inside 0..63).
inline uint64_t three_bits(int lo) {
  if (lo >= 64 || lo < -2) return 0;
  return lo >= 0 ? uint64_t{7} << lo : uint64_t{7} >> -lo;
}
template <int NC>
SM_AVX512 void wta_regs(const uint8_t* agg, int w, int nd, uint8_t* dw, uint8_t* c1, uint8_t* c2, uint8_t* cmax) {
  __mmask64 live[NC];
  for (int c = 0; c < NC; ++c) {
    const int n = std::clamp(nd - 64 * c, 0, 64);
    live[c] = n == 64 ? ~__mmask64{0} : (__mmask64{1} << n) - 1;
  }
  const __m512i ones = _mm512_set1_epi8(-1);
  for (int x = 0; x < w; ++x) {
    const uint8_t* a = agg + static_cast<size_t>(x) * nd;
    __m512i v[NC];
    __m512i lo = ones, hi = _mm512_setzero_si512();
    for (int c = 0; c < NC; ++c) {
      v[c] = _mm512_mask_loadu_epi8(ones, live[c], a + 64 * c);
      lo = _mm512_min_epu8(lo, v[c]);
      hi = _mm512_max_epu8(hi, _mm512_maskz_mov_epi8(live[c], v[c]));
    }
    const uint8_t m = least_byte(lo);
    const int top = 255 - least_byte(_mm512_xor_si512(hi, ones));
    int best = 0;
    for (int c = 0; c < NC; ++c) {
      const uint64_t eq = _mm512_cmpeq_epu8_mask(v[c], _mm512_set1_epi8(static_cast<char>(m))) & live[c];
      if (eq) {
        best = 64 * c + __builtin_ctzll(eq);
        break;
      }
    }
    __m512i rest = ones;  // the levels at least 2 from best
    for (int c = 0; c < NC; ++c)
      rest = _mm512_min_epu8(rest, _mm512_mask_mov_epi8(ones, live[c] & ~three_bits(best - 1 - 64 * c), v[c]));
    const bool any = best >= 2 || best + 2 < nd;
    dw[x] = static_cast<uint8_t>(best);
    c1[x] = m;
    c2[x] = any ? least_byte(rest) : m;
    cmax[x] = static_cast<uint8_t>(top);
  }
}
#undef SM_AVX512

// wta_regs for this nd where the CPU has the instructions (false: not run).
bool wta_avx512(const uint8_t* agg, int w, int nd, uint8_t* dw, uint8_t* c1, uint8_t* c2, uint8_t* cmax) {
  static const bool ok = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                         __builtin_cpu_supports("avx512vl") && std::getenv("SM_NO_AVX512") == nullptr;
  if (!ok) return false;
  switch ((nd + 63) / 64) {
    case 1:
      return wta_regs<1>(agg, w, nd, dw, c1, c2, cmax), true;
    case 2:
      return wta_regs<2>(agg, w, nd, dw, c1, c2, cmax), true;
    case 3:
      return wta_regs<3>(agg, w, nd, dw, c1, c2, cmax), true;
    case 4:
      return wta_regs<4>(agg, w, nd, dw, c1, c2, cmax), true;
    default:
      return false;
  }
}

// right_wta_regs for this nd where the CPU has the instructions (false: not run).
bool right_wta_avx512(const uint8_t* agg, int w, int nd, uint16_t* key) {
  static const bool ok = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512vbmi") &&
                         std::getenv("SM_NO_AVX512") == nullptr;
  if (!ok || w < 1) return false;
  switch ((nd + 31) / 32) {
    case 1:
      return right_wta_regs<1>(agg, w, nd, key), true;
    case 2:
      return right_wta_regs<2>(agg, w, nd, key), true;
    case 3:
      return right_wta_regs<3>(agg, w, nd, key), true;
    case 4:
      return right_wta_regs<4>(agg, w, nd, key), true;
    case 5:
      return right_wta_regs<5>(agg, w, nd, key), true;
    case 6:
      return right_wta_regs<6>(agg, w, nd, key), true;
    case 7:
      return right_wta_regs<7>(agg, w, nd, key), true;
    case 8:
      return right_wta_regs<8>(agg, w, nd, key), true;
    default:
      return false;
  }
}
#endif

}  // namespace

void right_wta(const uint8_t* agg, int w, int nd, std::vector<uint8_t>& out) {
  std::vector<uint16_t> key(static_cast<size_t>(w + nd), 0xffff);
#if defined(SM_X86_DISPATCH)
  if (!right_wta_avx512(agg, w, nd, key.data()))
#endif
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
