#include "dp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

// Speed (docs/performance.md): the forward pass is vectorized over levels, and on x86-64
// with GCC also compiled for AVX2 and picked at run time (SM_HOT in kernels.hpp);
// integer arithmetic only, same bits.
#include "kernels.hpp"
#include "parallel.hpp"

#if defined(SM_X86_DISPATCH)
#include <immintrin.h>
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

namespace {

// The forward pass works on U split by parity: ue[m] = U(i, 2m), uo[m] = U(i, 2m+1).
// cm: the matched costs in site order (see trellis_line), stride entries per row; dec:
// the choice of occlusion node (i, d) at i * stride + d / 2.
struct Fwd {
  int n, ne, no, stride;
  uint32_t occ, mask;
  const uint32_t* pen;  // nullptr: occ everywhere; else the penalty of DP clock t, level pair m at pen[t + m + 1]
  const uint16_t* cm;
  uint32_t* ue;
  uint32_t* uo;
  uint8_t* dec;
};

// One level at a time, straight from the recurrence (also the fallback for ACC_W > 30).
void forward_scalar(const Fwd& f) {
  // The first of choice 0 (u), 1 (c1) and 2 (c2) that reaches the minimum; a missing
  // choice is passed as 0xffffffff, which no sum below 2^ACC_W beats.
  auto occ_node = [](uint32_t& u, uint32_t c1, uint32_t c2, uint8_t& ch) {
    const bool t1 = c1 < u;
    const uint32_t b1 = t1 ? c1 : u;
    const bool t2 = c2 < b1;
    u = t2 ? c2 : b1;
    ch = static_cast<uint8_t>(t2 ? 2 : (t1 ? 1 : 0));
  };
  const uint32_t none = 0xffffffffu, mask = f.mask;
  uint32_t* ue = f.ue;
  uint32_t* uo = f.uo;
  for (int t = 0; t < f.n; ++t) {
    // Penalty of the occlusion nodes of level pair m (d = 2m+1 at site 2t+1, d = 2m at
    // site 2t+2): both have xl = t + m + 1.
    auto occ_at = [&f, t](int m) { return f.pen ? uint32_t{f.pen[t + m + 1]} : f.occ; };
    // Site 2t+1: occlusion nodes d = 2m+1 (d - 1 = 2m always exists, d + 1 = 2m+2
    // while m + 1 < ne) from the site-2t values, then the matched nodes d = 2m.
    uint8_t* dec = f.dec + static_cast<size_t>(2 * t + 1) * f.stride;
    for (int m = 0; m < f.no; ++m) {
      const uint32_t occ = occ_at(m);
      occ_node(uo[m], (ue[m] + occ) & mask, m + 1 < f.ne ? (ue[m + 1] + occ) & mask : none, dec[m]);
    }
    const uint16_t* c = f.cm + static_cast<size_t>(t) * f.stride;
    for (int m = 0; m < f.ne; ++m) ue[m] = (ue[m] + (c[m] & 0xffu)) & mask;
    // Site 2t+2: occlusion nodes d = 2m (d - 1 = 2m-1 for m >= 1, d + 1 = 2m+1 while
    // m < no) from the site-2t+1 values, then the matched nodes d = 2m+1.
    dec = f.dec + static_cast<size_t>(2 * t + 2) * f.stride;
    for (int m = 0; m < f.ne; ++m) {
      const uint32_t occ = occ_at(m);
      occ_node(ue[m], m >= 1 ? (uo[m - 1] + occ) & mask : none, m < f.no ? (uo[m] + occ) & mask : none, dec[m]);
    }
    c += f.stride;
    for (int m = 0; m < f.no; ++m) uo[m] = (uo[m] + (c[m] >> 8)) & mask;
  }
}

#if defined(__GNUC__)
// The same, one vector of levels of one parity at a time (GCC/Clang vector extensions,
// B bytes: SM_VEC_BYTES, or 64 in the AVX-512 variant chosen at run time). U stays
// below 2^30 here, so signed 32-bit compares are exact and a missing choice can be
// INT32_MAX. Every lane of the last vector is computed (lanes past the last level hold
// don't-care values in the padding of ue, uo and dec and never reach a real lane: a real
// lane reads a neighbour lane only where that choice exists).
template <int B>
struct Lanes {
  static constexpr int n = B / 4;
  typedef int32_t VI __attribute__((vector_size(B)));
  typedef uint16_t VHL __attribute__((vector_size(B / 2)));
  typedef uint8_t VD __attribute__((vector_size(B / 4)));
};

template <class V>
inline void load(V& v, const uint32_t* p) {
  std::memcpy(&v, p, sizeof v);
}
template <class V>
inline void store(uint32_t* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}

// Occlusion nodes from m, one vector: u = the first of choice 0 (u), 1 (lo + occ) and 2 (hi +
// occ) that reaches the minimum; lo_absent / hi_absent are INT32_MAX in the lanes that lack
// that choice, else 0. The choices are stored one byte per lane.
template <int B>
inline __attribute__((always_inline)) void occ_block(uint32_t* u, const uint32_t* lo, const uint32_t* hi,
                                                     const typename Lanes<B>::VI& occ, int32_t mask,
                                                     const typename Lanes<B>::VI& lo_absent,
                                                     const typename Lanes<B>::VI& hi_absent, uint8_t* dec) {
  using VI = typename Lanes<B>::VI;
  using VD = typename Lanes<B>::VD;
  VI b0, c1, c2;
  load(b0, u);
  load(c1, lo);
  load(c2, hi);
  c1 = ((c1 + occ) & mask) | lo_absent;
  c2 = ((c2 + occ) & mask) | hi_absent;
  const VI t1 = c1 < b0;            // -1 where true
  const VI b1 = c1 < b0 ? c1 : b0;  // (a minimum: one instruction where the unit has it)
  const VI t2 = c2 < b1;
  store(u, c2 < b1 ? c2 : b1);
  const VD ch = __builtin_convertvector((t2 & 2) | (t1 & 1), VD);  // 3 (both) reads as 2: choice 2 wins
  std::memcpy(dec, &ch, sizeof ch);
}

// u[m] = (u[m] + cost) & mask for one vector of lanes from m; cost = the low (odd =
// false) or high bytes of the 16-bit pairs at c.
template <int B>
inline __attribute__((always_inline)) void add_block(uint32_t* u, const uint16_t* c, bool odd, int32_t mask) {
  using VI = typename Lanes<B>::VI;
  typename Lanes<B>::VHL c16;
  std::memcpy(&c16, c, sizeof c16);
  const VI cv = __builtin_convertvector(odd ? c16 >> 8 : c16 & 0xff, VI);
  VI v;
  load(v, u);
  store(u, (v + cv) & mask);
}

// Wrap = false drops the "& mask" of every sum, which is exact when n <= MAX_WIDTH: a
// node's U grows by at most 255 per site from BIG or 0 (a matched node adds one 8-bit
// cost, an occlusion node at most one 8-bit penalty), so after 2n sites U <= BIG +
// 2 * MAX_WIDTH * 255 < 2^ACC_W (dp_acc_bits) and no sum wraps. (The padding lanes grow
// the same way.)
template <bool Wrap, int B>
inline __attribute__((always_inline)) void forward_body(const Fwd& f) {
  using VI = typename Lanes<B>::VI;
  constexpr int kLanes = Lanes<B>::n;
  VI lane;  // 0, 1, 2, ...
  for (int k = 0; k < kLanes; ++k) lane[k] = k;
  const VI no_lane = {};
  const VI first = lane == 0;
  const int32_t mask = Wrap ? static_cast<int32_t>(f.mask) : -1;  // -1: the ands fold away
  const VI occ_all = no_lane + static_cast<int32_t>(f.occ);
  // The penalties of lanes m..m+kLanes-1 at DP clock t (see forward_scalar): one
  // vector load (pen is widened to 32 bits per line, not gathered lane by lane).
  VI ov = occ_all;
  auto occ_v = [&f, &ov](int t, int m) -> const VI& {
    if (f.pen) std::memcpy(&ov, f.pen + t + m + 1, sizeof ov);
    return ov;
  };
  // The lanes without a choice, by block (the same at every t): choice 2 at site 2t+1 (d + 1
  // = 2m+2 past the last even level), choice 1 at site 2t+2 (lane 0 of block 0), choice 2
  // at site 2t+2 (2m+1 past the last odd level). At most 128 levels of a parity.
  constexpr int kBlocks = 128 / kLanes;
  VI odd_hi[kBlocks], even_lo[kBlocks], even_hi[kBlocks];
  if (f.stride > kBlocks * kLanes) return forward_scalar(f);  // (more than 256 levels: not a legal DISP)
  for (int m = 0, b = 0; m < f.stride; m += kLanes, ++b) {
    odd_hi[b] = (lane + (m + 1) >= f.ne) & INT32_MAX;
    even_lo[b] = (m == 0 ? first : no_lane) & INT32_MAX;
    even_hi[b] = (lane + m >= f.no) & INT32_MAX;
  }
  uint32_t* ue = f.ue;
  uint32_t* uo = f.uo;
  for (int t = 0; t < f.n; ++t) {
    uint8_t* dec = f.dec + static_cast<size_t>(2 * t + 1) * f.stride;
    for (int m = 0; m < f.no; m += kLanes)
      occ_block<B>(uo + m, ue + m, ue + m + 1, occ_v(t, m), mask, no_lane, odd_hi[m / kLanes], dec + m);
    const uint16_t* c = f.cm + static_cast<size_t>(t) * f.stride;
    for (int m = 0; m < f.ne; m += kLanes) add_block<B>(ue + m, c + m, false, mask);
    dec = f.dec + static_cast<size_t>(2 * t + 2) * f.stride;
    for (int m = 0; m < f.ne; m += kLanes)
      occ_block<B>(ue + m, uo + m - 1, uo + m, occ_v(t, m), mask, even_lo[m / kLanes], even_hi[m / kLanes], dec + m);
    c += f.stride;
    for (int m = 0; m < f.no; m += kLanes) add_block<B>(uo + m, c + m, true, mask);
  }
}

SM_HOT void forward_vector(const Fwd& f) { forward_body<true, SM_VEC_BYTES>(f); }
SM_HOT void forward_vector_nowrap(const Fwd& f) { forward_body<false, SM_VEC_BYTES>(f); }

#if defined(SM_X86_DISPATCH)
// The same recurrence with AVX-512 (chosen at run time where the CPU has it and
// SM_NO_AVX512 is not set; the tests run the other variant that way too): sixteen levels
// per vector, and the whole of U in registers (NB vectors per parity, NB = S / 16 <= 8),
// so the neighbour levels m - 1 and m + 1 are lane shifts (valignd) instead of loads that
// straddle the previous stores. A missing choice is a cleared compare-mask lane. Same
// arithmetic, so the same bits.
#define SM_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl")))

// The decisions of one vector of occlusion nodes: 1 where choice 1 won, 2 (or 3) where
// choice 2 did (the byte encoding of forward_scalar and forward_body).
SM_AVX512 inline void store_choices(uint8_t* dec, __mmask16 t1, __mmask16 t2) {
  const __m128i c = _mm_mask_mov_epi8(_mm_maskz_mov_epi8(t1, _mm_set1_epi8(1)), t2, _mm_set1_epi8(2));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(dec), c);
}

// (The zero-masked forms with every lane kept: the plain ones start from an undefined
// vector that GCC 12 warns about.)

// Occlusion nodes u from the neighbour values lo (choice 1) and hi (choice 2), penalty occ;
// has1 / has2: the lanes that have that choice.
template <bool Wrap>
SM_AVX512 inline __m512i occ_nodes(__m512i u, __m512i lo, __m512i hi, __m512i occ, __m512i mask, __mmask16 has1,
                                   __mmask16 has2, uint8_t* dec) {
  __m512i c1 = _mm512_add_epi32(lo, occ), c2 = _mm512_add_epi32(hi, occ);
  if (Wrap) {
    c1 = _mm512_and_si512(c1, mask);
    c2 = _mm512_and_si512(c2, mask);
  }
  const __mmask16 t1 = _mm512_mask_cmplt_epi32_mask(has1, c1, u);
  const __m512i b1 = _mm512_mask_mov_epi32(u, t1, c1);
  const __mmask16 t2 = _mm512_mask_cmplt_epi32_mask(has2, c2, b1);
  store_choices(dec, t1, t2);
  return _mm512_mask_mov_epi32(b1, t2, c2);
}

// u + the low (odd = false) or high bytes of the sixteen 16-bit cost pairs at c.
template <bool Wrap>
SM_AVX512 inline __m512i add_costs(__m512i u, const uint16_t* c, bool odd, __m512i mask) {
  const __m512i c32 = _mm512_maskz_cvtepu16_epi32(0xffff, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c)));
  const __m512i v = _mm512_add_epi32(
      u, odd ? _mm512_maskz_srli_epi32(0xffff, c32, 8) : _mm512_and_si512(c32, _mm512_set1_epi32(0xff)));
  return Wrap ? _mm512_and_si512(v, mask) : v;
}

template <bool Wrap, int NB>
SM_AVX512 void forward_regs(const Fwd& f) {
  __m512i ue[NB + 1], uo[NB + 1], occ[NB];  // (entry NB: lanes past the last level)
  __mmask16 odd_has2[NB], even_has1[NB], even_has2[NB];
  const __m512i mask = _mm512_set1_epi32(static_cast<int>(f.mask));
  auto lanes_below = [](int n) {
    return n >= 16 ? __mmask16(0xffff) : n <= 0 ? __mmask16(0) : __mmask16((1u << n) - 1);
  };
  for (int b = 0; b < NB; ++b) {
    ue[b] = _mm512_loadu_si512(f.ue + 16 * b);
    uo[b] = _mm512_loadu_si512(f.uo + 16 * b);
    occ[b] = _mm512_set1_epi32(static_cast<int>(f.occ));
    odd_has2[b] = lanes_below(f.ne - 16 * b - 1);  // d + 1 = 2m + 2 exists
    even_has1[b] = b == 0 ? __mmask16(0xfffe) : __mmask16(0xffff);
    even_has2[b] = lanes_below(f.no - 16 * b);  // 2m + 1 exists
  }
  ue[NB] = uo[NB] = _mm512_setzero_si512();
  for (int t = 0; t < f.n; ++t) {
    if (f.pen)
      for (int b = 0; b < NB; ++b) occ[b] = _mm512_loadu_si512(f.pen + t + 16 * b + 1);
    uint8_t* dec = f.dec + static_cast<size_t>(2 * t + 1) * f.stride;
    const uint16_t* c = f.cm + static_cast<size_t>(t) * f.stride;
#pragma GCC unroll 8
    for (int b = 0; b < NB; ++b)  // site 2t+1: occlusion nodes d = 2m+1 from d = 2m, 2m+2
      uo[b] = occ_nodes<Wrap>(uo[b], ue[b], _mm512_maskz_alignr_epi32(0xffff, ue[b + 1], ue[b], 1), occ[b], mask,
                              0xffff, odd_has2[b], dec + 16 * b);
#pragma GCC unroll 8
    for (int b = 0; b < NB; ++b) ue[b] = add_costs<Wrap>(ue[b], c + 16 * b, false, mask);
    dec = f.dec + static_cast<size_t>(2 * t + 2) * f.stride;
#pragma GCC unroll 8
    for (int b = NB - 1; b >= 0; --b)  // site 2t+2: occlusion nodes d = 2m from d = 2m-1, 2m+1
      ue[b] = occ_nodes<Wrap>(ue[b], _mm512_maskz_alignr_epi32(0xffff, uo[b], b > 0 ? uo[b - 1] : uo[b], 15), uo[b],
                              occ[b], mask, even_has1[b], even_has2[b], dec + 16 * b);
#pragma GCC unroll 8
    for (int b = 0; b < NB; ++b) uo[b] = add_costs<Wrap>(uo[b], c + f.stride + 16 * b, true, mask);
  }
  for (int b = 0; b < NB; ++b) {
    _mm512_storeu_si512(f.ue + 16 * b, ue[b]);
    _mm512_storeu_si512(f.uo + 16 * b, uo[b]);
  }
}

// forward_regs for S = 16 * nb.
template <bool Wrap>
void forward_avx512(const Fwd& f) {
  switch (f.stride / 16) {
    case 1:
      return forward_regs<Wrap, 1>(f);
    case 2:
      return forward_regs<Wrap, 2>(f);
    case 3:
      return forward_regs<Wrap, 3>(f);
    case 4:
      return forward_regs<Wrap, 4>(f);
    case 5:
      return forward_regs<Wrap, 5>(f);
    case 6:
      return forward_regs<Wrap, 6>(f);
    case 7:
      return forward_regs<Wrap, 7>(f);
    case 8:
      return forward_regs<Wrap, 8>(f);
    default:
      return forward_scalar(f);  // (more than 256 levels: not a legal DISP)
  }
}
#undef SM_AVX512

bool dp_avx512() {
  static const bool ok = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                         __builtin_cpu_supports("avx512vl") && std::getenv("SM_NO_AVX512") == nullptr;
  return ok;
}
#endif

// The vector variant for this CPU (wrap: sums masked to ACC_W bits).
void forward_vectors(const Fwd& f, bool wrap) {
#if defined(SM_X86_DISPATCH)
  if (dp_avx512()) return wrap ? forward_avx512<true>(f) : forward_avx512<false>(f);
#endif
  wrap ? forward_vector(f) : forward_vector_nowrap(f);
}
#endif

// Matched costs in site order, levels 2p and 2p+1 as one 16-bit pair: row t holds
// A(t+p, 2p) | A(t+p, 2p+1) << 8, the cost of node (2t+1, 2p) in the low byte and of
// node (2t, 2p+1) in the high byte (so site 2t+2 takes the high bytes of row t+1);
// beyond the line (xl = t + p >= n) the cost is 0. Rows 0..n, stride pairs each. (A
// strided gather; the forward pass then reads consecutive pairs.)
void gather_costs(const uint8_t* agg, int n, int nd, int ne, int no, int stride, uint16_t* cm) {
  for (int t = 0; t <= n; ++t) {
    uint16_t* row = cm + static_cast<size_t>(t) * stride;
    const uint8_t* a = agg + static_cast<size_t>(t) * nd;
    const int pmax = std::max(0, std::min(ne, n - t));
    const int pairs = std::min(pmax, no);  // odd DISP: the last even level has no pair
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#pragma GCC unroll 8
    for (int p = 0; p < pairs; ++p)  // the pair as one 16-bit load: c[0] | c[1] << 8
      std::memcpy(&row[p], a + static_cast<size_t>(p) * (nd + 2), 2);
#else
    for (int p = 0; p < pairs; ++p) {
      const uint8_t* c = a + static_cast<size_t>(p) * (nd + 2);
      row[p] = static_cast<uint16_t>(c[0] | c[1] << 8);
    }
#endif
    int p = pairs;
    if (p < pmax) row[p++] = a[static_cast<size_t>(pairs) * (nd + 2)];
    for (; p < stride; ++p) row[p] = 0;
  }
}

#if defined(SM_X86_DISPATCH)
// gather_costs with AVX-512 for ne a multiple of 32 (even DISP): cm[t][p] = P[t + p][p],
// P[x][p] the 16-bit pair p of pixel x, is a transpose, a shift of row p by p, and a
// transpose back: pt[p][x] = P[x][p] (zero for x >= n), then cm[t][p] = pt[p][t + p].
// Both transposes run on 8 x 8 blocks of pairs, four side by side in the 128-bit lanes of
// a 512-bit vector (unpacks work within lanes). cm gets rows 0 .. n rounded up to 8.
#define SM_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl")))
// Transposes the 8 x 8 block in each 128-bit lane of r[0..7] (row i, 8 entries) in place.
// (Zero-masked forms with every lane kept here and below: the plain ones start from an
// undefined vector that GCC 12 warns about.)
SM_AVX512 inline void transpose_lanes8x8(__m512i* r) {
  __m512i b[8], c[8];
  for (int i = 0; i < 4; ++i) {
    b[2 * i] = _mm512_maskz_unpacklo_epi16(~__mmask32{0}, r[2 * i], r[2 * i + 1]);
    b[2 * i + 1] = _mm512_maskz_unpackhi_epi16(~__mmask32{0}, r[2 * i], r[2 * i + 1]);
  }
  for (int i = 0; i < 2; ++i) {
    c[4 * i] = _mm512_maskz_unpacklo_epi32(0xffff, b[4 * i], b[4 * i + 2]);
    c[4 * i + 1] = _mm512_maskz_unpackhi_epi32(0xffff, b[4 * i], b[4 * i + 2]);
    c[4 * i + 2] = _mm512_maskz_unpacklo_epi32(0xffff, b[4 * i + 1], b[4 * i + 3]);
    c[4 * i + 3] = _mm512_maskz_unpackhi_epi32(0xffff, b[4 * i + 1], b[4 * i + 3]);
  }
  for (int i = 0; i < 4; ++i) {
    r[2 * i] = _mm512_maskz_unpacklo_epi64(0xff, c[i], c[4 + i]);
    r[2 * i + 1] = _mm512_maskz_unpackhi_epi64(0xff, c[i], c[4 + i]);
  }
}

// The four 128-bit lanes of v to p, p + step, p + 2 step, p + 3 step. The lane index of
// the extract must be an immediate, so the lanes are written out (a loop index is one only
// once -O3 unrolls the loop: at -O2 (RelWithDebInfo) it is not and the build fails). maskz: the
// unmasked extract of GCC 12's header reads an undefined vector (-Wuninitialized).
SM_AVX512 inline void store_lanes(__m512i v, uint16_t* p, size_t step) {
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm512_maskz_extracti32x4_epi32(0xf, v, 0));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p + step), _mm512_maskz_extracti32x4_epi32(0xf, v, 1));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p + 2 * step), _mm512_maskz_extracti32x4_epi32(0xf, v, 2));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p + 3 * step), _mm512_maskz_extracti32x4_epi32(0xf, v, 3));
}

// pt[p][x] = P[x][p] for pixels x0 .. x0+7 and pairs p0 .. p0+31 (row stride ptw).
SM_AVX512 inline void pairs_to_rows(const uint16_t* pairs, int ne, int x0, int p0, uint16_t* pt, size_t ptw) {
  __m512i r[8];
  for (int i = 0; i < 8; ++i) r[i] = _mm512_loadu_si512(pairs + static_cast<size_t>(x0 + i) * ne + p0);
  transpose_lanes8x8(r);
  for (int k = 0; k < 8; ++k)  // lane j of r[k]: pair p0 + 8j + k of the 8 pixels
    store_lanes(r[k], pt + static_cast<size_t>(p0 + k) * ptw + x0, 8 * ptw);
}

// cm[t][p] = pt[p][t + p] for t0 .. t0+7 and pairs p0 .. p0+31.
SM_AVX512 inline void rows_to_sites(const uint16_t* pt, size_t ptw, int t0, int p0, uint16_t* cm, int stride) {
  __m512i r[8];
  for (int i = 0; i < 8; ++i) {  // lane j of row i: pt[p0 + 8j + i][t0 + p0 + 8j + i ..]
    auto at = [&](int j) {
      const int p = p0 + 8 * j + i;
      return _mm_loadu_si128(reinterpret_cast<const __m128i*>(pt + static_cast<size_t>(p) * ptw + t0 + p));
    };
    r[i] = _mm512_maskz_inserti32x4(
        0xffff,
        _mm512_maskz_inserti32x4(0xffff, _mm512_maskz_inserti32x4(0xffff, _mm512_zextsi128_si512(at(0)), at(1), 1),
                                 at(2), 2),
        at(3), 3);
  }
  transpose_lanes8x8(r);
  for (int k = 0; k < 8; ++k) _mm512_storeu_si512(cm + static_cast<size_t>(t0 + k) * stride + p0, r[k]);
}

SM_AVX512 void gather_costs_avx512(const uint8_t* agg, int n, int ne, int stride, uint16_t* cm,
                                   std::vector<uint16_t>& pt_buf) {
  const size_t ptw = static_cast<size_t>(n) + stride + 16;
  pt_buf.resize(static_cast<size_t>(ne) * ptw);
  uint16_t* pt = pt_buf.data();
  const auto* pairs = reinterpret_cast<const uint16_t*>(agg);  // (DISP even: pair p of x at x * ne + p)
  int x0 = 0;
  for (; x0 + 8 <= n; x0 += 8)
    for (int p0 = 0; p0 < ne; p0 += 32) pairs_to_rows(pairs, ne, x0, p0, pt, ptw);
  for (int p = 0; p < ne; ++p) {
    uint16_t* row = pt + static_cast<size_t>(p) * ptw;
    for (int x = x0; x < n; ++x) std::memcpy(&row[x], agg + static_cast<size_t>(x) * 2 * ne + 2 * p, 2);
    std::fill(row + n, row + ptw, uint16_t{0});
  }
  for (int t0 = 0; t0 <= n; t0 += 8)
    for (int p0 = 0; p0 < ne; p0 += 32) rows_to_sites(pt, ptw, t0, p0, cm, stride);
}
#undef SM_AVX512
#endif

}  // namespace

// Forward pass two sites at a time, like the hardware's clock t: site 2t+1 (matched
// nodes at even d, occlusion nodes at odd d), then site 2t+2 (matched at odd d,
// occlusion at even d). The levels are split by parity and the matched costs are
// gathered into site order first, so the loops over levels run over consecutive
// entries and vectorize.
namespace {
void trellis_line_impl(const uint8_t* agg, int n, uint8_t occ, const uint8_t* pen, const HwConfig& hw, DpScratch& s,
                       DpLine& out) {
  const int nd = hw.disp;
  const int acc_w = dp_acc_bits(hw);
  const uint32_t mask = (acc_w >= 32) ? 0xffffffffu : ((1u << acc_w) - 1);
  const uint32_t big = 1u << (acc_w - 1);
  const int sites = 2 * n;
  const int ne = (nd + 1) / 2, no = nd / 2;  // even / odd levels
  const int stride = (ne + 15) / 16 * 16;    // entries per site, whole vectors (up to 16 lanes)

  s.cm.resize(static_cast<size_t>(n + 8) * stride);
#if defined(SM_X86_DISPATCH)
  if (dp_avx512() && nd % 2 == 0 && ne % 32 == 0 && ne == stride)
    gather_costs_avx512(agg, n, ne, stride, s.cm.data(), s.pt);
  else
#endif
    gather_costs(agg, n, nd, ne, no, stride, s.cm.data());

  // U with one vector of room in front (index -1 is read by the first block) and
  // behind. Every decision the backward pass reads is written by the forward pass, so
  // dec is not cleared.
  s.u0.assign(static_cast<size_t>(stride) + 2 * 16, big);
  s.u1.assign(static_cast<size_t>(stride) + 2 * 16, big);
  s.dec.resize(static_cast<size_t>(sites + 1) * stride);
  // Per-pixel penalties padded to every lane the vector pass reads (t + m + 1 < n + stride + 16);
  // nodes with xl > n never reach the end node, so the padding value does not matter.
  const uint32_t* penp = nullptr;
  if (pen) {
    s.pen.assign(static_cast<size_t>(n) + stride + 16, pen[n]);
    std::copy(pen, pen + n + 1, s.pen.begin());
    penp = s.pen.data();
  }
  const Fwd f{n, ne, no, stride, occ, mask, penp, s.cm.data(), s.u0.data() + 16, s.u1.data() + 16, s.dec.data()};
  f.ue[0] = 0;
#if defined(__GNUC__)
  if (acc_w <= 30)
    forward_vectors(f, n > hw.max_width);
  else
#endif
    forward_scalar(f);
  out.end_cost = f.ue[0];

  // Backward pass from (2N, 0).
  out.path.assign(sites + 1, 0);
  out.match.assign(n, -1);
  int d = 0;
  for (int i = sites; i >= 1; --i) {
    out.path[i] = d;
    if ((i + d) & 1) {
      out.match[(i - 1 + d) / 2] = d;
    } else {
      const uint32_t ch = s.dec[static_cast<size_t>(i) * stride + d / 2];
      d += (ch & 2) ? 1 : (ch == 1) ? -1 : 0;  // 2 or 3: choice 2 (the vector pass's encoding)
    }
  }
  out.path[0] = d;
  dp_fill(out.match, out.disp);
}
}  // namespace

void trellis_line(const uint8_t* agg, int n, uint8_t occ, const HwConfig& hw, DpScratch& s, DpLine& out) {
  trellis_line_impl(agg, n, occ, nullptr, hw, s, out);
}

void trellis_line_pen(const uint8_t* agg, int n, const uint8_t* pen, const HwConfig& hw, DpScratch& s, DpLine& out) {
  trellis_line_impl(agg, n, 0, pen, hw, s, out);
}

void edge_penalties(const uint8_t* left, int n, uint8_t occ, uint8_t occ_edge, uint8_t edge_t,
                    std::vector<uint8_t>& pen) {
  pen.assign(static_cast<size_t>(n) + 1, occ);
  uint8_t* const p = pen.data();
  for (int x = 1; x < n; ++x)  // (a select, not a conditional store: the loop vectorises)
    p[x] = std::abs(static_cast<int>(left[x]) - static_cast<int>(left[x - 1])) > edge_t ? occ_edge : occ;
}

DispImage trellis_dp_edge(const CostVolume& agg, const Image8& left, uint8_t occ, uint8_t occ_edge, uint8_t edge_t,
                          const HwConfig& hw, int threads) {
  if (agg.d != hw.disp || left.w != agg.w || left.h != agg.h)
    throw std::invalid_argument("trellis_dp_edge: cost volume, DISP and left image disagree");
  DispImage out(agg.w, agg.h);
  parallel_bands(agg.h, threads, [&](int y0, int y1, int) {
    DpScratch s;
    DpLine line;
    std::vector<uint8_t> pen;
    for (int y = y0; y < y1; ++y) {
      edge_penalties(&left.px[static_cast<size_t>(y) * left.w], agg.w, occ, occ_edge, edge_t, pen);
      trellis_line_pen(agg.pix(0, y), agg.w, pen.data(), hw, s, line);
      std::copy(line.disp.begin(), line.disp.end(), &out.at(0, y));
    }
  });
  return out;
}

void dp_fill(const std::vector<int>& match, std::vector<DispPix>& disp) {
  const int n = static_cast<int>(match.size());
  disp.resize(static_cast<size_t>(n));
  int x = 0;
  while (x < n && match[x] < 0) ++x;
  // Left of the first match: disp(first) (0 when the line has no match).
  std::fill(disp.begin(), disp.begin() + x, make_disp(x < n ? match[x] : 0, true));
  // Each match, then the pixels up to the next one: min(disp(a), disp(b)) between two
  // matches, disp(last) right of the last. (Every pixel written once.)
  while (x < n) {
    const int m = match[x];
    disp[x] = make_disp(m, true);
    int e = x + 1;
    while (e < n && match[e] < 0) ++e;
    std::fill(disp.begin() + x + 1, disp.begin() + e, make_disp(e < n ? std::min(m, match[e]) : m, true));
    x = e;
  }
}

DispImage trellis_dp(const CostVolume& agg, uint8_t occ, const HwConfig& hw, int threads) {
  if (agg.d != hw.disp)
    throw std::invalid_argument(fmt::format("trellis_dp: cost volume has {} levels, DISP is {}", agg.d, hw.disp));
  if (agg.w > hw.max_width || agg.w < 1)
    throw std::invalid_argument(fmt::format("trellis_dp: width {} outside 1..MAX_WIDTH={}", agg.w, hw.max_width));
  DispImage out(agg.w, agg.h);
  parallel_bands(agg.h, threads, [&](int y0, int y1, int) {
    DpScratch s;
    DpLine line;
    for (int y = y0; y < y1; ++y) {
      trellis_line(agg.pix(0, y), agg.w, occ, hw, s, line);
      std::copy(line.disp.begin(), line.disp.end(), &out.at(0, y));
    }
  });
  return out;
}

}  // namespace sm
