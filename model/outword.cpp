#include "outword.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "confidence.hpp"
#include "kernels.hpp"
#include "parallel.hpp"
#include "subpix.hpp"
#include "validity.hpp"

namespace sm {

namespace {

// The bodies of out_fields and out_word, inlined into make_output's pixel loop (as calls
// they were half of the stage's time).
[[gnu::always_inline]] inline OutFields fields_at(const Evidence& ev, int x, int y, int nd, const OutputRegs& r) {
  OutFields f;
  f.d = ev.d.at(x, y);
  f.off = static_cast<int8_t>(subpix_q4(ev, x, y, nd, r) - 16 * f.d);
  // the rules that do not depend on the output level (the border, x < d_out, does)
  const unsigned fails = valid_failures(ev, x, y, f.d, r) & enabled_rules(r) & ~unsigned{kFailBorder};
  f.fail = fails != 0;
  f.border_en = r.occ_en != 0;
  const uint8_t c = confidence(ev, x, y, f.d);
  f.lr_ok = (c & kConfLrOk) != 0;
  f.matched = ev.matched.at(x, y) != 0;
  f.agree_ok = (c & kConfAgreeOk) != 0;
  f.ratio = static_cast<uint8_t>(f.fail ? fails_slot(fails) : c & kConfRatio);
  f.fb = !r.occ_en && r.fill_bg && !f.matched ? ev.fill_bg.at(x, y) : static_cast<uint8_t>(nd - 1);
  return f;
}

[[gnu::always_inline]] inline int level_of(const OutFields& f, DispPix p) {
  return std::min<int>(f.fb, static_cast<int>(disp_value(p)));
}

[[gnu::always_inline]] inline uint32_t word_of(const OutFields& f, DispPix p, int x, int nd) {
  const int post_d = static_cast<int>(disp_value(p));
  // the background fill replaces a nearer level and carries no fraction
  const bool bg = f.fb < post_d;
  const int d_out = level_of(f, p);
  const int q4 = bg ? 16 * d_out : subpix_after_post(16 * f.d + f.off, f.d, post_d);
  const bool border = x < d_out;
  const bool border_fail = f.border_en && border;
  const bool valid = disp_valid(p) && !f.fail && !border_fail;
  const unsigned conf = (f.lr_ok ? kConfLrOk : 0u) | (f.matched && !border ? kConfMatched : 0u) |
                        (f.agree_ok ? kConfAgreeOk : 0u) | f.ratio;
  return make_out_word(valid, conf, static_cast<unsigned>(std::clamp(q4, 0, 16 * (nd - 1))),
                       fails_from_slot(f.fail ? f.ratio : 0u, border_fail));
}

#if defined(SM_X86_DISPATCH)
// fields_at and word_of (conf_variant 0) for sixteen pixels at a time with AVX-512 (chosen
// at run time where the CPU has it and SM_NO_AVX512 is not set; tests run the other path
// that way): the same arithmetic on vectors of 32-bit lanes (GCC vector extensions; a
// condition is a lane of -1 or 0, selects are element-wise), without the two divisions,
// which become restoring divisions (one quotient bit per step, as the RTL divides). The
// per-pixel loop was 10% of the model's time. Requires C2 >= C1 at every pixel (always so
// for a WTA record: C1 is the least cost), where the confidence ratio 32 (C2 - C1) / (C2 + 1)
// is 0..31: make_output checks the row and takes the per-pixel path otherwise.
#define SM_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl")))
typedef int32_t VI __attribute__((vector_size(64)));  // 16 pixels
typedef uint8_t VB16 __attribute__((vector_size(16)));
typedef uint16_t VH16 __attribute__((vector_size(32)));

SM_AVX512 inline VI load_u8(const uint8_t* p) {
  VB16 v;
  std::memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, VI);
}

// floor(n / d) for 0 <= n < d << Bits, d > 0, per lane: restoring division, one quotient
// bit per step from the top.
template <int Bits>
SM_AVX512 inline VI restoring_div(VI n, VI d) {
  VI q = {};
  for (int b = Bits - 1; b >= 0; --b) {
    const VI take = n >= (d << b);
    n -= take & (d << b);
    q |= take & (1 << b);
  }
  return q;
}

// fit_q4 (subpix.hpp) per lane: min(q, 8) of its quotient q is a 4-bit restoring division
// (a larger quotient sets all four bits, 15, clamped to 8).
SM_AVX512 inline VI fit_q4_lanes(VI cm, VI c0, VI cp, int fit) {
  const VI num = cm - cp;
  const VI up = cm - c0, dn = cp - c0;
  const VI den = fit == 0 ? 2 * (cm - 2 * c0 + cp) : 2 * (up > dn ? up : dn);
  const VI an = num < 0 ? -num : num;
  VI m = restoring_div<4>(32 * an + den, 2 * (den > 0 ? den : 1));
  m = m > 8 ? 8 : m;
  return den <= 0 ? 0 : num < 0 ? -m : m;
}

// Pixels x0 .. x0+15 of row y.
SM_AVX512 void output_lanes(const Evidence& ev, const DispPix* post, int y, int x0, int nd, const OutputRegs& r,
                            uint32_t* out) {
  const auto at = [x0, y](const Image8& p) SM_AVX512 { return load_u8(&p.at(x0, y)); };
  const VI d = at(ev.d), dw = at(ev.dw), c1 = at(ev.c1), c2 = at(ev.c2), lr = at(ev.lr);
  const VI matched = at(ev.matched) != 0;
  const int top = nd - 1;
  // subpix_q4 (the estimator and its enable are the same for every pixel)
  VI q4v = 16 * d;
  if (r.subpix_en && r.subpix_src == 0) {
    const VI ok = (d != 0) & (d != top);
    q4v = ok ? q4v + fit_q4_lanes(at(ev.cm), at(ev.c0), at(ev.cp), r.subpix_fit) : q4v;
  } else if (r.subpix_en) {
    const VI e0 = at(ev.band[0]), e1 = at(ev.band[1]), e2 = at(ev.band[2]), e3 = at(ev.band[3]), e4 = at(ev.band[4]);
    const VI dif = d - dw;
    if (r.subpix_src == 1) {
      const VI ok = (dif >= -1) & (dif <= 1) & (dw != 0) & (dw != top);
      q4v = ok ? 16 * dw + fit_q4_lanes(e1, e2, e3, r.subpix_fit) : q4v;
    } else {
      const VI j = dif + 2;  // d's index in the band
      const VI ok = (j >= 1) & (j <= 3) & (d != 0) & (d != top);
      const VI a = j == 1   ? e0
                   : j == 2 ? e1
                            : e2,
               b = j == 1   ? e1
                   : j == 2 ? e2
                            : e3,
               c = j == 1   ? e2
                   : j == 2 ? e3
                            : e4;
      q4v = ok ? q4v + fit_q4_lanes(a, b, c, r.subpix_fit) : q4v;
    }
  }
  // the rules that do not depend on the output level, and the confidence bits
  const VI ddw = d > dw ? d - dw : dw - d, lrd = lr > d ? lr - d : d - lr;
  const VI none = {};
  VI fails = none;  // ValidFail bits of the enabled rules that fail (the border's below)
  if (r.occ_en) fails |= ~matched & (at(ev.gap) > r.occ_t) & int32_t{kFailOcc};
  if (r.uniq_en) fails |= (c2 - c1 < r.uniq_t) & int32_t{kFailUniq};
  if (r.agree_en) fails |= (ddw > r.agree_t) & int32_t{kFailAgree};
  if (r.tex_en) fails |= (at(ev.cmax) - c1 < r.tex_t) & int32_t{kFailTex};
  if (r.lr_en) fails |= (lrd > r.lr_t) & int32_t{kFailLr};
  const VI fail = fails != 0;
  const VI ratio = restoring_div<5>(32 * (c2 - c1), c2 + 1);  // < 32: C2 - C1 < C2 + 1
  // word_of
  VH16 pv16;
  std::memcpy(&pv16, post + x0, sizeof pv16);
  const VI pv = __builtin_convertvector(pv16, VI);
  const VI post_d = pv & 0x7fff;
  const VI fb = (!r.occ_en && r.fill_bg) ? (matched ? top : at(ev.fill_bg)) : none + top;
  const VI bg = fb < post_d;
  const VI d_out = bg ? fb : post_d;
  VI q4 = bg ? 16 * d_out : post_d == d ? q4v : 16 * post_d;
  q4 = q4 < 0 ? 0 : q4 > 16 * top ? 16 * top : q4;
  VI x = {};
  for (int k = 0; k < 16; ++k) x[k] = x0 + k;
  const VI border = x < d_out;
  const VI border_fail = r.occ_en ? border : none;
  const VI valid = ((pv & kDispValid) != 0) & ~fail & ~border_fail;
  const VI conf = ((lrd <= 1) & 0x80) | (matched & ~border & 0x40) | ((ddw <= 1) & 0x20) | ratio;
  const VI word = valid ? (static_cast<int32_t>(kOutValid) | conf << 16 | q4)
                        : (fails | (border_fail & int32_t{kFailBorder})) << 24;
  std::memcpy(out + x0, &word, sizeof word);
}

bool output_avx512() {
  static const bool ok = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                         __builtin_cpu_supports("avx512vl") && std::getenv("SM_NO_AVX512") == nullptr;
  return ok;
}
#undef SM_AVX512
#endif

}  // namespace

OutFields out_fields(const Evidence& ev, int x, int y, int nd, const OutputRegs& r) {
  return fields_at(ev, x, y, nd, r);
}
int out_level(const OutFields& f, DispPix p) { return level_of(f, p); }
uint32_t out_word(const OutFields& f, DispPix p, int x, int nd) { return word_of(f, p, x, nd); }

void make_output_rows(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int conf_variant, int y0,
                      int y1, OutImage& out) {
  for (int y = y0; y < y1; ++y) {
    int x = 0;
#if defined(SM_X86_DISPATCH)
    int below = 0;  // output_lanes' condition: C2 >= C1 on the row
    const uint8_t *const c1 = &ev.c1.at(0, y), *const c2 = &ev.c2.at(0, y);
    for (int k = 0; k < post.w; ++k) below |= c2[k] < c1[k];
    if (conf_variant == 0 && below == 0 && output_avx512())
      for (; x + 16 <= post.w; x += 16) output_lanes(ev, &post.at(0, y), y, x, nd, r, &out.at(0, y));
#endif
    for (; x < post.w; ++x) {
      const OutFields f = fields_at(ev, x, y, nd, r);
      uint32_t w = word_of(f, post.at(x, y), x, nd);
      if (conf_variant != 0 && out_valid(w))  // the study's alternatives to the specified bits
        w = (w & ~0xff0000u) | uint32_t{confidence(ev, x, y, out_level(f, post.at(x, y)), conf_variant)} << 16;
      out.at(x, y) = w;
    }
  }
}

OutImage make_output(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int conf_variant,
                     int threads) {
  if (post.w != ev.d.w || post.h != ev.d.h) throw std::invalid_argument("make_output: evidence and post sizes differ");
  OutImage out(post.w, post.h);
  parallel_bands(post.h, threads,
                 [&](int y0, int y1, int) { make_output_rows(ev, post, nd, r, conf_variant, y0, y1, out); });
  return out;
}

void object_levels_rows(const OutImage& out, int y0, int y1, DispImage& d) {
  for (size_t i = static_cast<size_t>(y0) * out.w; i < static_cast<size_t>(y1) * out.w; ++i) {
    const uint32_t w = out.px[i];
    d.px[i] = out_valid(w) ? make_disp((out_q4(w) + 8) >> 4, true) : make_disp(0, false);
  }
}

DispImage object_levels(const OutImage& out) {
  DispImage d(out.w, out.h);
  object_levels_rows(out, 0, out.h, d);
  return d;
}

}  // namespace sm
