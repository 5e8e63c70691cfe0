#include "outword.hpp"

#include <algorithm>
#include <stdexcept>

#include "confidence.hpp"
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
  const unsigned on = (r.occ_en ? kFailOcc : 0u) | (r.uniq_en ? kFailUniq : 0u) | (r.agree_en ? kFailAgree : 0u) |
                      (r.tex_en ? kFailTex : 0u) | (r.lr_en ? kFailLr : 0u);
  f.fail = (valid_failures(ev, x, y, f.d, r) & on) != 0;
  f.border_en = r.occ_en != 0;
  const uint8_t c = confidence(ev, x, y, f.d);
  f.lr_ok = (c & 0x80) != 0;
  f.matched = ev.matched.at(x, y) != 0;
  f.agree_ok = (c & 0x20) != 0;
  f.ratio = c & 0x1f;
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
  const bool valid = disp_valid(p) && !f.fail && !(f.border_en && border);
  const unsigned conf = f.lr_ok << 7 | (f.matched && !border) << 6 | f.agree_ok << 5 | f.ratio;
  return make_out_word(valid, conf, static_cast<unsigned>(std::clamp(q4, 0, 16 * (nd - 1))));
}

}  // namespace

OutFields out_fields(const Evidence& ev, int x, int y, int nd, const OutputRegs& r) {
  return fields_at(ev, x, y, nd, r);
}
int out_level(const OutFields& f, DispPix p) { return level_of(f, p); }
uint32_t out_word(const OutFields& f, DispPix p, int x, int nd) { return word_of(f, p, x, nd); }

OutImage make_output(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int conf_variant,
                     int threads) {
  if (post.w != ev.d.w || post.h != ev.d.h) throw std::invalid_argument("make_output: evidence and post sizes differ");
  OutImage out(post.w, post.h);
  parallel_bands(post.h, threads, [&](int y0, int y1, int) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < post.w; ++x) {
        const OutFields f = fields_at(ev, x, y, nd, r);
        uint32_t w = word_of(f, post.at(x, y), x, nd);
        if (conf_variant != 0 && out_valid(w))  // the study's alternatives to the specified bits
          w = (w & ~0xff0000u) | uint32_t{confidence(ev, x, y, out_level(f, post.at(x, y)), conf_variant)} << 16;
        out.at(x, y) = w;
      }
  });
  return out;
}

DispImage object_levels(const OutImage& out) {
  DispImage d(out.w, out.h);
  for (size_t i = 0; i < out.px.size(); ++i) {
    const uint32_t w = out.px[i];
    d.px[i] = out_valid(w) ? make_disp((out_q4(w) + 8) >> 4, true) : make_disp(0, false);
  }
  return d;
}

}  // namespace sm
