#include "aggregate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "kernels.hpp"

#if defined(SM_X86_DISPATCH)
#include <immintrin.h>
#endif
#include "parallel.hpp"

namespace sm {

namespace detail {

AggRow::AggRow(int w_, int h_, int nd_, int sw, const std::array<uint8_t, 32>& table, const HwConfig& hw)
    : w(w_),
      h(h_),
      nd(nd_),
      r((sw - 1) / 2),
      out_max((1u << hw.cost_bits()) - 1),
      // Byte sums of `group` costs cannot wrap: group * (255 >> COST_SHIFT) <= 255, for
      // any 8-bit input, not only legal Hamming costs (4 at COST_SHIFT 2, 1 at 0).
      group(255 / (255 >> std::clamp(hw.cost_shift, 0, 7))),
      code{},
      recip{} {
  for (size_t s = 0; s < recip.size(); ++s) recip[s] = static_cast<uint16_t>(sw_recip(static_cast<uint32_t>(s)));
  for (int k = 0; k < 256; ++k) {
    const uint32_t wq = sw_weight(table, k);
    code[static_cast<size_t>(k)] = static_cast<uint8_t>(wq == 4 ? 3 : wq == 2 ? 2 : wq);
  }
}

// The level loop uses GCC/Clang vector extensions; its zero-extension (bytes interleaved
// with zero bytes, read as 16-bit lanes) assumes a little-endian target.
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define SM_AGG_VECTORS 1
#endif

// The weight codes of 16 pixels at a time are looked up with GCC's variable
// __builtin_shuffle (one byte shuffle on x86); Clang has no such builtin.
#if defined(__GNUC__) && !defined(__clang__)
#define SM_AGG_CODE_SHUFFLE 1
#endif

namespace {

#if defined(SM_AGG_CODE_SHUFFLE)
typedef uint8_t VB16 __attribute__((vector_size(16)));  // 16 pixels (weight codes)
#endif

#if defined(SM_AGG_VECTORS)
// 32 levels per byte vector (32 bytes). Costs are summed in bytes over groups of
// neighbours with the same weight, then widened once per group and added in 16 bits (the
// weights applied by doubling between weight classes): one widening per `group` neighbours instead of a
// widening and a multiply per neighbour. The 16-bit sums are exact: the largest,
// 4*SW*SW*CMAX (43904 at SW 7, CENSUS 15, COST_SHIFT 0; 49980 for any 8-bit input),
// fits, and a byte sum is at most group * (255 >> COST_SHIFT) <= 255.
typedef uint8_t VB __attribute__((vector_size(32)));
typedef uint16_t VH __attribute__((vector_size(32)));

// (Vectors are passed by reference: by value they would change the ABI between clones.)
inline void load_add(VB& s, const uint8_t* p) {
  VB v;
  std::memcpy(&v, p, sizeof v);
  s += v;
}

// A_raw of the 32 * NB levels d0 .. d0 + 32*NB - 1 of one pixel into sum[0 .. 32*NB-1].
// Bit q of mask[c] marks window position q as a neighbour of weight 1 << c; its costs
// start at base[q] + xoff.
template <int NB>
inline void agg_block(const uint8_t* const* base, size_t xoff, const uint64_t* mask, int group, int d0, uint16_t* sum) {
  const VB zero = {};
  VH lo[NB], hi[NB];  // levels 0-7 and 16-23 / 8-15 and 24-31 of each block of 32
  for (int v = 0; v < NB; ++v) lo[v] = hi[v] = VH{};
  // Weights 4, 2, 1 in turn, the sums so far doubled between them (Horner: 2 * (2 * S4 +
  // S2) + S1 = 4 S4 + 2 S2 + S1, exact in 16 bits as the final sum is), instead of a
  // shift per group.
  for (int c = 2; c >= 0; --c) {
    if (c < 2)
      for (int v = 0; v < NB; ++v) {
        lo[v] += lo[v];
        hi[v] += hi[v];
      }
    uint64_t bits = mask[c];
    while (bits) {
      VB s[NB];
      for (int v = 0; v < NB; ++v) s[v] = zero;
      for (int k = 0; k < group && bits; ++k) {
        const uint8_t* q = base[__builtin_ctzll(bits)] + xoff + d0;
        bits &= bits - 1;
        for (int v = 0; v < NB; ++v) load_add(s[v], q + 32 * v);
      }
      // Zero-extension by interleaving with zero bytes within each 16-byte half (one
      // instruction each on x86); the level order is restored when storing.
      for (int v = 0; v < NB; ++v) {
        const VB l = __builtin_shufflevector(s[v], zero, 0, 32, 1, 32, 2, 32, 3, 32, 4, 32, 5, 32, 6, 32, 7, 32, 16, 32,
                                             17, 32, 18, 32, 19, 32, 20, 32, 21, 32, 22, 32, 23, 32);
        const VB h = __builtin_shufflevector(s[v], zero, 8, 32, 9, 32, 10, 32, 11, 32, 12, 32, 13, 32, 14, 32, 15, 32,
                                             24, 32, 25, 32, 26, 32, 27, 32, 28, 32, 29, 32, 30, 32, 31, 32);
        lo[v] += reinterpret_cast<const VH&>(l);
        hi[v] += reinterpret_cast<const VH&>(h);
      }
    }
  }
  for (int v = 0; v < NB; ++v) {
    uint16_t* o = sum + 32 * v;
    std::memcpy(o, &lo[v], 16);
    std::memcpy(o + 8, &hi[v], 16);
    std::memcpy(o + 16, reinterpret_cast<const char*>(&lo[v]) + 16, 16);
    std::memcpy(o + 24, reinterpret_cast<const char*>(&hi[v]) + 16, 16);
  }
}
#endif  // SM_AGG_VECTORS

// A = min((A_raw * RECIP(wsum) + 2048) >> 12, 2^CW - 1) of one pixel; the product needs 32 bits.
inline void normalise(const uint16_t* su, int nd, uint32_t rec, uint32_t out_max, uint8_t* o) {
  for (int d = 0; d < nd; ++d) {
    const uint32_t v = (su[d] * rec + (1u << (kRecipShift - 1))) >> kRecipShift;
    o[d] = static_cast<uint8_t>(std::min(v, out_max));
  }
}

// The weight masks of centre x: window positions of weight 1, 2, 4 (codes 1, 2, 3), and
// RECIP of their weight sum (from the table: a division per pixel was 7% of the stage).
inline void weight_masks(const AggRow& a, uint64_t b0, uint64_t b1, uint64_t* m, uint32_t& rec) {
  m[0] = b0 & ~b1;
  m[1] = b1 & ~b0;
  m[2] = b0 & b1;
  rec = a.recip[static_cast<size_t>(__builtin_popcountll(m[0]) + 2 * __builtin_popcountll(m[1]) +
                                    4 * __builtin_popcountll(m[2]))];
}

#if defined(SM_X86_DISPATCH)
// Steps (2) and (3) of agg_row with AVX-512 (chosen at run time): 64 levels per vector,
// the same sums as agg_block, normalised in registers. The byte sums are widened by
// interleaving with zero bytes within each 128-bit lane (levels 0-7 | 16-23 | ... in
// `lo`, 8-15 | 24-31 | ... in `hi`), and packing the normalised 16-bit values back to
// bytes interleaves the same way, so the levels come out in order.
#define SM_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl")))

// The normalisation of one pixel: A = min((A_raw * RECIP + 2048) >> 12, 2^CW - 1) with
// 16-bit products. For RECIP <= 2048 (every weight sum but 1), with P = A_raw * (RECIP
// << 4), (A_raw * RECIP + 2048) >> 12 = (P + 32768) >> 16 = hi16(P) + (lo16(P) >> 15);
// RECIP = 4096 (weight sum 1) gives A_raw itself.
struct Norm512 {
  bool unit;
  __m512i r16, top;
};
SM_AVX512 inline Norm512 norm512(uint32_t rec, uint32_t out_max) {
  const bool unit = rec >= (1u << kRecipShift);
  return {unit, _mm512_set1_epi16(static_cast<short>(unit ? 0 : rec << 4)),
          _mm512_set1_epi16(static_cast<short>(out_max))};
}
SM_AVX512 inline __m512i normalise512(const Norm512& n, __m512i s) {
  const __m512i v =
      n.unit ? s : _mm512_add_epi16(_mm512_mulhi_epu16(s, n.r16), _mm512_srli_epi16(_mm512_mullo_epi16(s, n.r16), 15));
  return _mm512_min_epu16(v, n.top);
}

// The NB vectors' 16-bit sums of levels 64 v .. 64 v + 63 (low and high halves of each
// byte lane pair) normalised, packed to bytes and stored at o, levels nlev and up left
// untouched.
template <int NB>
SM_AVX512 inline void store_levels512(const __m512i* lo, const __m512i* hi, const Norm512& nrm, uint8_t* o, int nlev) {
  for (int v = 0; v < NB; ++v) {
    const __m512i bytes = _mm512_packus_epi16(normalise512(nrm, lo[v]), normalise512(nrm, hi[v]));
    const int left = nlev - 64 * v;
    if (left >= 64)
      _mm512_storeu_si512(o + 64 * v, bytes);
    else if (left > 0)
      _mm512_mask_storeu_epi8(o + 64 * v, (__mmask64{1} << left) - 1, bytes);
  }
}

// A of the 64 * NB levels d0 .. of one pixel into o[0 .. nlev-1] (nlev <= 64 * NB: the
// last block's lanes past the last level are computed and not stored).
template <int NB>
SM_AVX512 inline void agg_block512(const uint8_t* const* base, size_t xoff, const uint64_t* mask, int group, int d0,
                                   const Norm512& nrm, uint8_t* o, int nlev) {
  const __m512i zero = _mm512_setzero_si512();
  __m512i lo[NB], hi[NB];
  for (int v = 0; v < NB; ++v) lo[v] = hi[v] = zero;
  for (int c = 2; c >= 0; --c) {  // weights 4, 2, 1, doubled in between (as agg_block)
    if (c < 2)
      for (int v = 0; v < NB; ++v) {
        lo[v] = _mm512_add_epi16(lo[v], lo[v]);
        hi[v] = _mm512_add_epi16(hi[v], hi[v]);
      }
    uint64_t bits = mask[c];
    while (bits) {
      __m512i s[NB];
      for (int v = 0; v < NB; ++v) s[v] = zero;
      for (int k = 0; k < group && bits; ++k) {
        const uint8_t* q = base[__builtin_ctzll(bits)] + xoff + d0;
        bits &= bits - 1;
        for (int v = 0; v < NB; ++v) s[v] = _mm512_add_epi8(s[v], _mm512_loadu_si512(q + 64 * v));
      }
      for (int v = 0; v < NB; ++v) {
        lo[v] = _mm512_add_epi16(lo[v], _mm512_unpacklo_epi8(s[v], zero));
        hi[v] = _mm512_add_epi16(hi[v], _mm512_unpackhi_epi8(s[v], zero));
      }
    }
  }
  store_levels512<NB>(lo, hi, nrm, o, nlev);
}

// agg_block512 for a centre whose whole window lies in the row, without a branch that
// depends on the weights: every window position's costs are read, two positions at a time
// interleaved byte by byte (level k of both side by side) and multiplied by their weights
// 0, 1, 2, 4 (vpmaddubsw: w1 C1 + w2 C2 in 16 bits, at most 2 * 255 * 4), so the loop runs
// the same steps for every centre (agg_block512's loops end where the weights say, and
// those branches were most of its time). Same 16-bit sums, so the same bits. pos[q]: the
// costs of window position q (padded to an even count with a position of weight 0); byte q
// of wb: the weight of position q.
template <int NB>
SM_AVX512 inline void agg_pairs512(const uint8_t* const* pos, int npairs, const uint64_t* wb, size_t off,
                                   const Norm512& nrm, uint8_t* o, int nlev) {
  __m512i lo[NB], hi[NB];
  for (int v = 0; v < NB; ++v) lo[v] = hi[v] = _mm512_setzero_si512();
  for (int p = 0; p < npairs; ++p) {
    // (Two bytes at a time from wb as stored: a whole-vector copy of it would wait for
    // the stores to retire, no store forwarding from four 8-byte stores.)
    uint16_t wpair;
    std::memcpy(&wpair, reinterpret_cast<const char*>(wb) + 2 * p, sizeof wpair);
    const __m512i wv = _mm512_set1_epi16(static_cast<short>(wpair));
    const uint8_t* q1 = pos[2 * p] + off;
    const uint8_t* q2 = pos[2 * p + 1] + off;
    for (int v = 0; v < NB; ++v) {
      const __m512i c1 = _mm512_loadu_si512(q1 + 64 * v), c2 = _mm512_loadu_si512(q2 + 64 * v);
      lo[v] = _mm512_add_epi16(lo[v], _mm512_maddubs_epi16(_mm512_unpacklo_epi8(c1, c2), wv));
      hi[v] = _mm512_add_epi16(hi[v], _mm512_maddubs_epi16(_mm512_unpackhi_epi8(c1, c2), wv));
    }
  }
  store_levels512<NB>(lo, hi, nrm, o, nlev);
}

// The weight of every window position of one centre as a byte (position q at byte q of
// wb, 0 past the last): the mask bits deposited into bytes (pdep), weight 1, 2 or 4.
__attribute__((target("bmi2"))) inline void weight_bytes(const uint64_t* m, int nq, uint64_t* wb) {
  constexpr uint64_t ones = 0x0101010101010101ull;
  for (int k = 0; k < (nq + 7) / 8; ++k)
    wb[k] = _pdep_u64(m[0] >> (8 * k) & 0xff, ones) | _pdep_u64(m[1] >> (8 * k) & 0xff, 2 * ones) |
            _pdep_u64(m[2] >> (8 * k) & 0xff, 4 * ones);
}

// pos: base with rows outside the image pointing at the centre row instead (read, weight 0).
SM_AVX512 __attribute__((target("bmi2"))) void agg_pixels_avx512(const AggRow& a, const uint64_t* b0,
                                                                 const uint64_t* b1, const uint8_t* const* base,
                                                                 const uint8_t* const* pos, uint8_t* out) {
  const int nd = a.nd, r = a.r, nq = (2 * r + 1) * (2 * r + 1), npairs = (nq + 1) / 2;
  for (int x = 0; x < a.w; ++x) {
    uint64_t m[3];
    uint32_t rec;
    weight_masks(a, b0[x], b1[x], m, rec);
    const Norm512 nrm = norm512(rec, a.out_max);
    const size_t xoff = static_cast<size_t>(x) * nd;
    uint8_t* o = out + xoff;
    int d0 = 0;
    if (x >= r && x + r < a.w) {  // the whole window inside the row: every position readable
      alignas(64) uint64_t wb[8] = {};
      weight_bytes(m, nq, wb);
      for (; d0 + 128 <= nd; d0 += 128) agg_pairs512<2>(pos, npairs, wb, xoff + d0, nrm, o + d0, 128);
      for (; d0 < nd; d0 += 64) agg_pairs512<1>(pos, npairs, wb, xoff + d0, nrm, o + d0, std::min(64, nd - d0));
      continue;
    }
    for (; d0 + 128 <= nd; d0 += 128) agg_block512<2>(base, xoff, m, a.group, d0, nrm, o + d0, 128);
    for (; d0 < nd; d0 += 64) agg_block512<1>(base, xoff, m, a.group, d0, nrm, o + d0, std::min(64, nd - d0));
  }
}
#undef SM_AVX512

bool agg_avx512() {
  static const bool ok = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("bmi2") &&
                         std::getenv("SM_NO_AVX512") == nullptr;  // (tests of the other kernels)
  return ok;
}
#endif

}  // namespace

// One row in three steps: (1) the weight code of every (centre, window position) pair,
// one window position at a time across the row (vectorizes), kept per centre as bit
// masks; (2) per centre, the weight sum from the masks; (3) per centre and block of
// levels, the neighbours' costs summed by weight (agg_block), then the normalisation.
SM_HOT void agg_row(const AggRow& a, const uint8_t* const* c_rows, const uint8_t* left, int y, uint8_t* out) {
  const int w = a.w, h = a.h, nd = a.nd, r = a.r, side = 2 * r + 1, nq = side * side;
  // (1) Window position q = (j + r) * side + (i + r) is neighbour (x + i, y + j) of
  // centre (x, y). Bit q of b0[x] / b1[x] is bit 0 / 1 of its weight code (0 outside
  // the image); SW <= 7 gives at most 49 positions per 64-bit word.
  thread_local std::vector<uint64_t> bits;  // scratch per thread (no allocation per row)
  bits.assign(2 * static_cast<size_t>(w), 0);
  uint64_t* b0 = bits.data();
  uint64_t* b1 = b0 + w;
  thread_local std::vector<uint8_t> code_buf;  // every entry written per window position
  code_buf.resize(static_cast<size_t>(w));
  uint8_t* const code = code_buf.data();
#if defined(SM_AGG_CODE_SHUFFLE)
  // The code only depends on |dI| >> 3 (0..31): two 16-entry tables for a byte shuffle.
  VB16 tab0, tab1;
  for (int k = 0; k < 16; ++k) {
    tab0[k] = a.code[static_cast<size_t>(8 * k)];
    tab1[k] = a.code[static_cast<size_t>(8 * (k + 16))];
  }
#endif
  const uint8_t* centre = left + static_cast<size_t>(y) * w;
  for (int j = -r; j <= r; ++j) {
    if (y + j < 0 || y + j >= h) continue;  // codes stay 0
    const uint8_t* nrow = left + static_cast<size_t>(y + j) * w;
    for (int i = -r; i <= r; ++i) {
      const int x0 = std::max(0, -i), x1 = std::min(w, w - i);  // neighbour inside
      std::fill(code, code + x0, 0);
      std::fill(code + x1, code + w, 0);
      int x = x0;
#if defined(SM_AGG_CODE_SHUFFLE)
      for (; x + 16 <= x1; x += 16) {
        VB16 pq, pc;
        std::memcpy(&pq, nrow + x + i, 16);
        std::memcpy(&pc, centre + x, 16);
        const VB16 diff = pq > pc ? pq - pc : pc - pq;
        const VB16 k = (diff >> 3) & 15;  // |dI| >> 3 is k, or k + 16 when |dI| >= 128
        const VB16 c = diff >= 128 ? __builtin_shuffle(tab1, k) : __builtin_shuffle(tab0, k);
        std::memcpy(&code[static_cast<size_t>(x)], &c, 16);
      }
#endif
      for (; x < x1; ++x) code[static_cast<size_t>(x)] = a.code[static_cast<size_t>(std::abs(nrow[x + i] - centre[x]))];
      const int q = (j + r) * side + (i + r);
      for (x = 0; x < w; ++x) {
        b0[x] |= static_cast<uint64_t>(code[static_cast<size_t>(x)] & 1) << q;
        b1[x] |= static_cast<uint64_t>(code[static_cast<size_t>(x)] >> 1) << q;
      }
    }
  }
  // Costs of window position q for the centre x start at base[q] + x * nd.
  std::vector<const uint8_t*> base(static_cast<size_t>(nq), nullptr);
  for (int j = -r; j <= r; ++j)
    if (y + j >= 0 && y + j < h)
      for (int i = -r; i <= r; ++i)
        base[static_cast<size_t>((j + r) * side + (i + r))] = c_rows[j + r] + static_cast<ptrdiff_t>(i) * nd;

  std::vector<uint16_t> sum(static_cast<size_t>(nd) + 128);  // A_raw, whole blocks
  uint16_t* su = sum.data();
#if defined(SM_X86_DISPATCH)
  if (agg_avx512()) {
    std::vector<const uint8_t*> pos(static_cast<size_t>(nq) + 1);
    for (int j = -r; j <= r; ++j)
      for (int i = -r; i <= r; ++i) {
        const uint8_t* row = (y + j >= 0 && y + j < h) ? c_rows[j + r] : c_rows[r];
        pos[static_cast<size_t>((j + r) * side + (i + r))] = row + static_cast<ptrdiff_t>(i) * nd;
      }
    pos[static_cast<size_t>(nq)] = pos[0];  // (the pad of an odd count: weight 0)
    return agg_pixels_avx512(a, b0, b1, base.data(), pos.data(), out);
  }
#endif
  for (int x = 0; x < w; ++x) {
    // (2) Window positions of weight 1, 2, 4 (codes 1, 2, 3) and the weight sum.
    uint64_t m[3];
    uint32_t rec;
    weight_masks(a, b0[x], b1[x], m, rec);
    const size_t xoff = static_cast<size_t>(x) * nd;
    // (3) A_raw, widest blocks of levels first (each block is independent; the last one
    // may read past level nd - 1, into kCostPad, and those lanes are not used).
#if defined(SM_AGG_VECTORS)
    int d0 = 0;
    for (; d0 + 128 <= nd; d0 += 128) agg_block<4>(base.data(), xoff, m, a.group, d0, su + d0);
    for (; d0 + 64 <= nd; d0 += 64) agg_block<2>(base.data(), xoff, m, a.group, d0, su + d0);
    for (; d0 < nd; d0 += 32) agg_block<1>(base.data(), xoff, m, a.group, d0, su + d0);
#else
    for (int d = 0; d < nd; ++d) {
      uint32_t s = 0;
      for (int c = 0; c < 3; ++c)
        for (int q = 0; q < nq; ++q)
          if (m[c] >> q & 1) s += static_cast<uint32_t>(base[q][xoff + d]) << c;
      su[d] = static_cast<uint16_t>(s);
    }
#endif
    normalise(su, nd, rec, a.out_max, out + xoff);
  }
}

}  // namespace detail

CostVolume sw_aggregate(const CostVolume& raw, const Image8& left, const std::array<uint8_t, 32>& table,
                        const HwConfig& hw, int threads) {
  if (raw.w != left.w || raw.h != left.h)
    throw std::invalid_argument(
        fmt::format("sw_aggregate: cost volume {}x{} but left image {}x{}", raw.w, raw.h, left.w, left.h));
  if (raw.d != hw.disp)
    throw std::invalid_argument(fmt::format("sw_aggregate: cost volume has {} levels, DISP is {}", raw.d, hw.disp));
  if (hw.sw < 1 || hw.sw > 7 || hw.sw % 2 == 0)  // (a window position per bit of a word)
    throw std::invalid_argument(fmt::format("sw_aggregate: SW {} must be odd, 1..7", hw.sw));

  const int w = raw.w, h = raw.h, nd = raw.d;
  const detail::AggRow a(w, h, nd, hw.sw, table, hw);
  // C = H >> COST_SHIFT once for the whole volume (padded for the block reads).
  std::vector<uint8_t> c(raw.v.size() + detail::kCostPad);
  for (size_t i = 0; i < raw.v.size(); ++i) c[i] = static_cast<uint8_t>(raw.v[i] >> hw.cost_shift);

  CostVolume out(w, h, nd);
  const size_t row = static_cast<size_t>(w) * nd;
  parallel_bands(h, threads, [&](int y0, int y1, int) {
    std::vector<const uint8_t*> rows(static_cast<size_t>(2 * a.r + 1));
    for (int y = y0; y < y1; ++y) {
      for (int j = -a.r; j <= a.r; ++j)
        rows[static_cast<size_t>(j + a.r)] = (y + j >= 0 && y + j < h) ? c.data() + (y + j) * row : nullptr;
      detail::agg_row(a, rows.data(), left.px.data(), y, out.v.data() + y * row);
    }
  });
  return out;
}

}  // namespace sm
