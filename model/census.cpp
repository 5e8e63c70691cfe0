#include "census.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "kernels.hpp"
#include "parallel.hpp"

#if defined(SM_X86_DISPATCH)
#include <immintrin.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace sm {

namespace detail {

namespace {
constexpr int kBlock = SM_VEC_BYTES;  // pixels per vector of the census compare loop
}

CensusPad::CensusPad(const Image8& in, int r_)
    : w(in.w),
      h(in.h),
      r(r_),
      stride(static_cast<size_t>(in.w + 2 * r_ + std::max(kBlock, 64))),  // (64: census_planes_avx512)
      px(stride * static_cast<size_t>(in.h + 2 * r_)) {
  // Row y of the padded image is image row clamp(y, 0, h-1), each row extended with its
  // first pixel on the left and its last on the right (the vector tail included).
  for (int y = -r; y < h + r; ++y) {
    const uint8_t* src = &in.px[static_cast<size_t>(std::clamp(y, 0, h - 1)) * w];
    uint8_t* dst = px.data() + static_cast<size_t>(y + r) * stride;
    std::memset(dst, src[0], static_cast<size_t>(r));
    std::memcpy(dst + r, src, static_cast<size_t>(w));
    std::memset(dst + r + w, src[w - 1], stride - static_cast<size_t>(r + w));
  }
}

#if defined(__GNUC__)
typedef uint8_t VB __attribute__((vector_size(kBlock)));
#endif

#if defined(SM_X86_DISPATCH)
// The byte planes of census_row with AVX-512 (BW; chosen at run time where the CPU has it
// and SM_NO_AVX512 is not set): 64 pixels per compare, the compare an unsigned byte
// compare into a mask and the bit set by a masked add (the plane's bits are distinct, so
// adding is ORing). Same bits as the generic loop.
__attribute__((target("avx512f,avx512bw"))) void census_planes_avx512(const uint8_t* c, const uint8_t* const* nrow,
                                                                      int nb, size_t wr, uint8_t* pl) {
  for (size_t x = 0; x < wr; x += 64) {
    const __m512i cv = _mm512_loadu_si512(c + x);
    __m512i p = _mm512_setzero_si512();
    for (int b = 0; b < nb; ++b) {
      const __mmask64 lt = _mm512_cmplt_epu8_mask(_mm512_loadu_si512(nrow[b] + x), cv);
      p = _mm512_mask_add_epi8(p, lt, p, _mm512_set1_epi8(static_cast<char>(1u << b)));
    }
    _mm512_storeu_si512(pl + x, p);
  }
}

bool census_avx512() {
  static const bool ok =
      __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && std::getenv("SM_NO_AVX512") == nullptr;
  return ok;
}
#endif

// Eight census bits at a time: bit k of byte plane g is neighbour 8g + k (raster order,
// centre skipped), computed for a whole row with one compare per neighbour and block of
// pixels (the compare loop vectorizes); then each pixel's four words are assembled
// from its plane bytes ((CENSUS^2 - 1) / 8, 28 at CENSUS 15; the others are 0). The
// replicated border gives an outside neighbour the nearest inside pixel's value.
SM_HOT void census_row(const CensusPad& in, int y, CensusVec* out) {
  const int r = in.r, w = in.w, side = 2 * r + 1;
  const int nbits = side * side - 1, ngroups = (nbits + 7) / 8;
  size_t wr = static_cast<size_t>((w + kBlock - 1) / kBlock * kBlock);
#if defined(SM_X86_DISPATCH)
  // The AVX-512 planes run over whole blocks of 64 pixels (the padded rows hold them).
  const bool wr64 = census_avx512() && in.stride >= static_cast<size_t>(2 * r + (w + 63) / 64 * 64);
  if (wr64) wr = static_cast<size_t>((w + 63) / 64 * 64);
#endif
  // Scratch kept per thread (no allocation per row); the planes past the last group
  // are read as zero bits.
  // (A local pointer: stores through uint8_t pointers would otherwise make the compiler
  // reload the vector's data pointer.)
  thread_local std::vector<uint8_t> planes_buf;
  planes_buf.resize(32 * wr);
  uint8_t* const planes = planes_buf.data();
  std::fill(planes + ngroups * wr, planes + 32 * wr, uint8_t{0});
  const uint8_t* c = in.row(y);
  for (int g = 0; g < ngroups; ++g) {
    const uint8_t* nrow[8];
    const int nb = std::min(8, nbits - 8 * g);
    for (int b = 0; b < nb; ++b) {
      int k = 8 * g + b;
      if (k >= nbits / 2) ++k;  // skip the centre (window position nbits / 2)
      nrow[b] = in.row(y + k / side - r) + (k % side - r);
    }
    uint8_t* pl = &planes[static_cast<size_t>(g) * wr];
#if defined(SM_X86_DISPATCH)
    if (wr64) {
      census_planes_avx512(c, nrow, nb, wr, pl);
      continue;
    }
#endif
#if defined(__GNUC__)
    for (size_t x = 0; x < wr; x += kBlock) {
      VB cv, p = VB{};
      std::memcpy(&cv, c + x, sizeof cv);
      for (int b = 0; b < nb; ++b) {
        VB nv;
        std::memcpy(&nv, nrow[b] + x, sizeof nv);
        // a named uint8_t: a cast in the expression is an int to GCC's vector check
        // when -fsanitize=undefined instruments the shift ("involves truncation")
        const uint8_t bit = static_cast<uint8_t>(1u << b);
        p |= reinterpret_cast<VB>(nv < cv) & bit;
      }
      std::memcpy(pl + x, &p, sizeof p);
    }
#else
    for (size_t x = 0; x < wr; ++x) {
      unsigned p = 0;
      for (int b = 0; b < nb; ++b) p |= static_cast<unsigned>(nrow[b][x] < c[x]) << b;
      pl[x] = static_cast<uint8_t>(p);
    }
#endif
  }
  int x = 0;
#if defined(__SSE2__)
  // Sixteen pixels at a time: the 8 plane bytes of a word are an 8 x 16 byte transpose
  // (interleaving bytes, then 16-bit, then 32-bit pairs), byte b of the word from plane
  // 8i + b as below.
  for (; x + 16 <= w; x += 16)
    for (int i = 0; i < 4; ++i) {
      __m128i p[8];
      for (int b = 0; b < 8; ++b)
        p[b] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&planes[(8 * i + b) * wr + static_cast<size_t>(x)]));
      __m128i q[8], s[8];
      for (int b = 0; b < 4; ++b) {  // bytes of planes 2b, 2b+1: pixels 0-7, 8-15
        q[2 * b] = _mm_unpacklo_epi8(p[2 * b], p[2 * b + 1]);
        q[2 * b + 1] = _mm_unpackhi_epi8(p[2 * b], p[2 * b + 1]);
      }
      for (int b = 0; b < 2; ++b)  // 16-bit pairs of planes 4b..4b+3: pixels 0-3, 4-7, 8-11, 12-15
        for (int hf = 0; hf < 2; ++hf) {
          s[4 * b + 2 * hf] = _mm_unpacklo_epi16(q[4 * b + hf], q[4 * b + 2 + hf]);
          s[4 * b + 2 * hf + 1] = _mm_unpackhi_epi16(q[4 * b + hf], q[4 * b + 2 + hf]);
        }
      for (int k = 0; k < 4; ++k) {  // 32-bit halves: planes 0-3 and 4-7 of pixels 4k .. 4k+3
        const __m128i lo = _mm_unpacklo_epi32(s[k], s[4 + k]), hi = _mm_unpackhi_epi32(s[k], s[4 + k]);
        CensusVec* o = out + x + 4 * k;
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&o[0][static_cast<size_t>(i)]), lo);
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&o[1][static_cast<size_t>(i)]), _mm_unpackhi_epi64(lo, lo));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&o[2][static_cast<size_t>(i)]), hi);
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&o[3][static_cast<size_t>(i)]), _mm_unpackhi_epi64(hi, hi));
      }
    }
#endif
  for (; x < w; ++x) {
    for (int i = 0; i < 4; ++i) {
      uint64_t v = 0;
      for (int b = 0; b < 8; ++b) v |= static_cast<uint64_t>(planes[(8 * i + b) * wr + x]) << (8 * b);
      out[x][static_cast<size_t>(i)] = v;
    }
  }
}

namespace {

// popcount(a ^ b) of all four words: exact for any input vector. The sum is taken
// modulo 256 (an 8-bit H) before the shift, as H >> COST_SHIFT of an 8-bit volume.
// Levels d .. nd-1 of left pixel x one at a time, the levels without a right pixel (x - d
// < 0) at the census bits cb. Always inlined, so that a kernel's tail is compiled with the
// kernel's instruction set (popcnt).
__attribute__((always_inline)) inline void cost_levels_scalar(const CensusVec* l, const CensusVec* rr, int x, int d,
                                                              int nd, uint8_t cb, int shift, uint8_t* o) {
  const int dn = std::min(nd, x + 1);  // levels with x - d >= 0
  for (; d < dn; ++d) {
    const CensusVec &p = l[x], &q = rr[x - d];
    int s = 0;
    for (size_t i = 0; i < 4; ++i) s += __builtin_popcountll(p[i] ^ q[i]);
    o[d] = static_cast<uint8_t>(static_cast<uint8_t>(s) >> shift);
  }
  if (d < nd) std::memset(o + d, cb >> shift, static_cast<size_t>(nd - d));  // (one byte at a time: 5% of the model)
}

void cost_row_portable(const CensusVec* l, const CensusVec* rr, int w, int nd, uint8_t cb, int shift, uint8_t* out) {
  for (int x = 0; x < w; ++x) cost_levels_scalar(l, rr, x, 0, nd, cb, shift, out + static_cast<size_t>(x) * nd);
}

#if defined(SM_X86_DISPATCH)
// The same with AVX2, eight levels at a time: the 256-bit XOR of a level is counted per
// byte with a nibble table (two byte shuffles; the nibbles of a ^ b are those of a XOR
// those of b, so each vector is split into nibbles once), the 32 byte counts summed per
// 64-bit quarter (psadbw, <= 64 each), the quarters of eight levels packed one byte per
// level and added bytewise: modulo 256 like the portable sum.
__attribute__((target("avx2,popcnt"))) void cost_row_avx2(const CensusVec* l, const CensusVec* rr, int w, int nd,
                                                          uint8_t cb, int shift, uint8_t* out) {
  const __m256i low4 = _mm256_set1_epi8(0x0f);
  const __m256i count4 = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4,  //
                                          0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4);
  const __m256i zero = _mm256_setzero_si256();
  // Right vectors split into low / high nibbles, 32 bytes each per pixel.
  thread_local std::vector<uint8_t> nib_buf;  // scratch per thread, every entry read is written below
  nib_buf.resize(64 * static_cast<size_t>(w));
  uint8_t* const nib = nib_buf.data();
  for (int x = 0; x < w; ++x) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&rr[x]));
    uint8_t* n = &nib[64 * static_cast<size_t>(x)];
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(n), _mm256_and_si256(v, low4));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(n + 32), _mm256_and_si256(_mm256_srli_epi16(v, 4), low4));
  }
  const __m128i sh = _mm_cvtsi32_si128(shift);
  const __m128i keep = _mm_set1_epi8(static_cast<char>(0xff >> shift));  // 16-bit shift: mask
  for (int x = 0; x < w; ++x) {
    uint8_t* o = out + static_cast<size_t>(x) * nd;
    const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&l[x]));
    const __m256i al = _mm256_and_si256(a, low4);
    const __m256i ah = _mm256_and_si256(_mm256_srli_epi16(a, 4), low4);
    const int dn = std::min(nd, x + 1);  // levels with x - d >= 0
    int d = 0;
    for (; d + 8 <= dn; d += 8) {
      __m256i packed = zero;  // byte k of each quarter: level d + k
      for (int k = 0; k < 8; ++k) {
        const uint8_t* b = &nib[64 * static_cast<size_t>(x - d - k)];
        const __m256i bl = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b));
        const __m256i bh = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + 32));
        const __m256i c = _mm256_add_epi8(_mm256_shuffle_epi8(count4, _mm256_xor_si256(al, bl)),
                                          _mm256_shuffle_epi8(count4, _mm256_xor_si256(ah, bh)));
        packed = _mm256_or_si256(packed, _mm256_slli_epi64(_mm256_sad_epu8(c, zero), 8 * k));
      }
      __m128i s = _mm_add_epi8(_mm256_castsi256_si128(packed), _mm256_extracti128_si256(packed, 1));
      s = _mm_add_epi8(s, _mm_unpackhi_epi64(s, s));
      s = _mm_and_si128(_mm_srl_epi16(s, sh), keep);
      _mm_storel_epi64(reinterpret_cast<__m128i*>(o + d), s);
    }
    cost_levels_scalar(l, rr, x, d, nd, cb, shift, o);  // the last levels one at a time
  }
}
#endif

#if defined(SM_X86_DISPATCH)
// The same with AVX-512 (VPOPCNTDQ, VNNI, VBMI, BW, VL; chosen at run time where the CPU
// has them), sixteen levels per step (costs16), then eight: the right vectors of levels
// d .. d+7 are the 256 contiguous bytes from rr[x - d - 7]; four 512-bit XORs with the left vector (twice),
// VPOPCNTQ per 64-bit word (<= 64), the words truncated to bytes (vpmovqb), the four of a
// level summed by vpdpbusd with ones, and the sums truncated to bytes (vpmovdb: modulo
// 256 like the portable sum), levels d+7 .. d reversed into order.
#define SM_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512vpopcntdq,avx512vnni,avx512vbmi")))
// Byte permutes that gather the low bytes of the 64 word counts of 16 levels into one
// vector (VBMI): stage 1 joins the 8 + 8 counts of two vectors, stage 2 two such halves,
// stage 3 the two quarters, group i (bytes 4i .. 4i+3, one level's four words) taken from
// the group of level d + i (the vectors hold levels d+15, d+14 | d+13, d+12 | ...).
struct Gather16 {
  __m512i s1, s2, s3;
};
SM_AVX512 inline Gather16 gather16() {
  alignas(64) uint8_t i1[64] = {}, i2[64] = {}, i3[64];
  for (int k = 0; k < 16; ++k) i1[k] = static_cast<uint8_t>(k < 8 ? 8 * k : 64 + 8 * (k - 8));
  for (int k = 0; k < 32; ++k) i2[k] = static_cast<uint8_t>(k < 16 ? k : 64 + k - 16);
  for (int i = 0; i < 16; ++i)
    for (int e = 0; e < 4; ++e) {
      const int g = 15 - i;  // group g of [u0 bytes 0..31 | u1 bytes 0..31] is level d + 15 - g
      i3[4 * i + e] = static_cast<uint8_t>(g < 8 ? 4 * g + e : 64 + 4 * (g - 8) + e);
    }
  return {_mm512_load_si512(i1), _mm512_load_si512(i2), _mm512_load_si512(i3)};
}
// The 16 costs of levels d .. d+15 (before the shift) of left vector a (broadcast), right
// vectors from b = &rr[x - d - 15], modulo 256.
SM_AVX512 inline __m128i costs16(__m512i a, const __m512i* b, const Gather16& g) {
  __m512i z[8], t[4];
  for (int j = 0; j < 8; ++j) z[j] = _mm512_popcnt_epi64(_mm512_xor_si512(a, _mm512_loadu_si512(b + j)));
  for (int k = 0; k < 4; ++k) t[k] = _mm512_permutex2var_epi8(z[2 * k], g.s1, z[2 * k + 1]);
  const __m512i u0 = _mm512_permutex2var_epi8(t[0], g.s2, t[1]), u1 = _mm512_permutex2var_epi8(t[2], g.s2, t[3]);
  const __m512i v = _mm512_permutex2var_epi8(u0, g.s3, u1);
  const __m512i sums = _mm512_dpbusd_epi32(_mm512_setzero_si512(), v, _mm512_set1_epi8(1));  // dword i: level d+i
  return _mm512_maskz_cvtepi32_epi8(0xffff, sums);
}

SM_AVX512 void cost_row_avx512(const CensusVec* l, const CensusVec* rr, int w, int nd, uint8_t cb, int shift,
                               uint8_t* out) {
  const Gather16 g = gather16();
  const __m256i ones = _mm256_set1_epi8(1);
  const __m128i rev = _mm_setr_epi8(7, 6, 5, 4, 3, 2, 1, 0, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m128i sh = _mm_cvtsi32_si128(shift);
  const __m128i keep = _mm_set1_epi8(static_cast<char>(0xff >> shift));  // 16-bit shift: mask
  for (int x = 0; x < w; ++x) {
    uint8_t* o = out + static_cast<size_t>(x) * nd;
    // (Zero-masked forms of the broadcast and truncations with all lanes kept: the plain ones
    // start from an undefined vector that GCC 12 warns about.)
    const __m512i a = _mm512_maskz_broadcast_i64x4(0xff, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&l[x])));
    const int dn = std::min(nd, x + 1);  // levels with x - d >= 0
    int d = 0;
    for (; d + 16 <= dn; d += 16) {
      const __m128i s = costs16(a, reinterpret_cast<const __m512i*>(&rr[x - d - 15]), g);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(o + d), _mm_and_si128(_mm_srl_epi16(s, sh), keep));
    }
    for (; d + 8 <= dn; d += 8) {
      const auto* b = reinterpret_cast<const __m512i*>(&rr[x - d - 7]);  // levels d+7, d+6 | d+5, d+4 | ...
      __m128i m[4];
      for (int j = 0; j < 4; ++j)
        m[j] = _mm512_maskz_cvtepi64_epi8(0xff, _mm512_popcnt_epi64(_mm512_xor_si512(a, _mm512_loadu_si512(b + j))));
      const __m256i bytes = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_unpacklo_epi64(m[0], m[1])),
                                                    _mm_unpacklo_epi64(m[2], m[3]), 1);
      const __m256i sums = _mm256_dpbusd_epi32(_mm256_setzero_si256(), bytes, ones);  // dword k: level d+7-k
      __m128i s = _mm_shuffle_epi8(_mm256_maskz_cvtepi32_epi8(0xff, sums), rev);
      s = _mm_and_si128(_mm_srl_epi16(s, sh), keep);
      _mm_storel_epi64(reinterpret_cast<__m128i*>(o + d), s);
    }
    cost_levels_scalar(l, rr, x, d, nd, cb, shift, o);  // the last levels one at a time
  }
}
#undef SM_AVX512
#endif

}  // namespace

void cost_row(const CensusVec* l, const CensusVec* rr, int w, int nd, uint8_t cb, int shift, uint8_t* out) {
#if defined(SM_X86_DISPATCH)
  static const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512vpopcntdq") &&
                             __builtin_cpu_supports("avx512vnni") && __builtin_cpu_supports("avx512vbmi") &&
                             std::getenv("SM_NO_AVX512") == nullptr;  // (tests of the AVX2 kernel)
  if (avx512) return cost_row_avx512(l, rr, w, nd, cb, shift, out);
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
  if (avx2) return cost_row_avx2(l, rr, w, nd, cb, shift, out);
#endif
  cost_row_portable(l, rr, w, nd, cb, shift, out);
}

namespace {

// n levels of one left pixel a against the right pixels q[0..n-1] (add_term_row's rule).
__attribute__((always_inline)) inline void add_term_span(uint8_t a, const uint8_t* q, int n, uint8_t mx, int as,
                                                         int shift, uint8_t cp, uint8_t* o) {
  for (int d = 0; d < n; ++d)  // min(o + t, cap), the sum in int
    o[d] = static_cast<uint8_t>(std::min(o[d] + (ad_term(a, q[d], as, mx) << shift), int{cp}));
}

// add_term_row on the reversed right row without vector code.
void add_term_portable(const uint8_t* l, const uint8_t* rev, int w, int nd, uint8_t mx, int as, int shift, uint8_t cp,
                       uint8_t* out) {
  for (int x = 0; x < w; ++x)
    add_term_span(l[x], rev + (w - 1 - x), std::min(nd, x + 1), mx, as, shift, cp, out + static_cast<size_t>(x) * nd);
}

#if defined(SM_X86_DISPATCH)
// The same with AVX2, 32 levels at a time: |a - b| as the OR of two saturating
// differences, the byte shifts as 16-bit shifts (right: masked to the byte; left: t <<
// shift <= 15 << 4 stays inside its byte), the sum saturating, then the cap.
__attribute__((target("avx2"))) void add_term_avx2(const uint8_t* l, const uint8_t* rev, int w, int nd, uint8_t mx,
                                                   int as, int shift, uint8_t cp, uint8_t* out) {
  const __m128i sa = _mm_cvtsi32_si128(as), ss = _mm_cvtsi32_si128(shift);
  const __m256i keep = _mm256_set1_epi8(static_cast<char>(0xff >> as));
  const __m256i vmx = _mm256_set1_epi8(static_cast<char>(mx)), vcp = _mm256_set1_epi8(static_cast<char>(cp));
  for (int x = 0; x < w; ++x) {
    const __m256i a = _mm256_set1_epi8(static_cast<char>(l[x]));
    const uint8_t* q = rev + (w - 1 - x);
    uint8_t* o = out + static_cast<size_t>(x) * nd;
    const int dn = std::min(nd, x + 1);
    int d = 0;
    for (; d + 32 <= dn; d += 32) {
      const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q + d));
      const __m256i diff = _mm256_or_si256(_mm256_subs_epu8(a, b), _mm256_subs_epu8(b, a));
      __m256i t = _mm256_min_epu8(_mm256_and_si256(_mm256_srl_epi16(diff, sa), keep), vmx);
      t = _mm256_sll_epi16(t, ss);
      auto* op = reinterpret_cast<__m256i*>(o + d);
      _mm256_storeu_si256(op, _mm256_min_epu8(_mm256_adds_epu8(_mm256_loadu_si256(op), t), vcp));
    }
    add_term_span(l[x], q + d, dn - d, mx, as, shift, cp, o + d);  // the last levels
  }
}
#endif

}  // namespace

void add_term_row(const uint8_t* l, const uint8_t* r, int w, int nd, const HwConfig& hw, int shift, int cap,
                  uint8_t* out) {
  if (hw.ad_max == 0) return;
  // The right row reversed: level d of pixel x reads rev[w - 1 - x + d], forward in d, so
  // the levels are byte-vector code (as a table lookup on r[x - d] the term took 20 of the
  // model's 44 ms per frame).
  thread_local std::vector<uint8_t> rev;  // scratch per thread, rewritten for every row
  rev.resize(static_cast<size_t>(w));
  for (int i = 0; i < w; ++i) rev[static_cast<size_t>(i)] = r[w - 1 - i];
  const auto mx = static_cast<uint8_t>(hw.ad_max), cp = static_cast<uint8_t>(cap);
#if defined(SM_X86_DISPATCH)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return add_term_avx2(l, rev.data(), w, nd, mx, hw.ad_shift, shift, cp, out);
#endif
  add_term_portable(l, rev.data(), w, nd, mx, hw.ad_shift, shift, cp, out);
}

}  // namespace detail

CensusImage census_transform(const Image8& in, const HwConfig& hw, int threads) {
  if (hw.census < 3 || hw.census > 15 || hw.census % 2 == 0)
    throw std::invalid_argument(fmt::format("census_transform: census {} must be odd, 3..15", hw.census));
  const detail::CensusPad pad(in, (hw.census - 1) / 2);
  CensusImage out(in.w, in.h, CensusVec{0, 0, 0, 0});
  parallel_bands(in.h, threads, [&](int y0, int y1, int) {
    for (int y = y0; y < y1; ++y) detail::census_row(pad, y, &out.px[static_cast<size_t>(y) * in.w]);
  });
  return out;
}

CostVolume hamming_cost(const CensusImage& cl, const CensusImage& cr, const HwConfig& hw, int threads) {
  if (cl.w != cr.w || cl.h != cr.h)
    throw std::invalid_argument(fmt::format("hamming_cost: left {}x{} and right {}x{} differ", cl.w, cl.h, cr.w, cr.h));
  if (hw.disp < 1 || hw.disp > 256)
    throw std::invalid_argument(fmt::format("hamming_cost: disp {} outside 1..256", hw.disp));
  const int nd = hw.disp, w = cl.w;
  const auto cb = static_cast<uint8_t>(hw.census_bits());
  CostVolume out(w, cl.h, nd);
  parallel_bands(cl.h, threads, [&](int y0, int y1, int) {
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y) * w;
      detail::cost_row(&cl.px[row], &cr.px[row], w, nd, cb, 0, out.v.data() + row * nd);
    }
  });
  return out;
}

CostVolume matching_cost(const CensusImage& cl, const CensusImage& cr, const Image8& left, const Image8& right,
                         const HwConfig& hw, int threads) {
  if (left.w != cl.w || left.h != cl.h || right.w != cl.w || right.h != cl.h)
    throw std::invalid_argument(fmt::format("matching_cost: images {}x{} and {}x{} differ from the census {}x{}",
                                            left.w, left.h, right.w, right.h, cl.w, cl.h));
  CostVolume out = hamming_cost(cl, cr, hw, threads);
  const int nd = hw.disp, w = cl.w, cb = hw.census_bits();
  parallel_bands(cl.h, threads, [&](int y0, int y1, int) {
    for (int y = y0; y < y1; ++y)
      detail::add_term_row(&left.px[static_cast<size_t>(y) * w], &right.px[static_cast<size_t>(y) * w], w, nd, hw,
                           hw.cost_shift, cb, out.v.data() + static_cast<size_t>(y) * w * nd);
  });
  return out;
}

}  // namespace sm
