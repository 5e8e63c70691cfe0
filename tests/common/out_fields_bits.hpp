// The bit layouts of the output stage's buses (rtl/sm_outfields.v, rtl/sm_outword.v):
// the fields that travel beside the disparity through the post filters, and the
// configuration word of the output registers. Shared by the block tests.
#pragma once

#include <cstdint>

#include "output_regs.hpp"
#include "outword.hpp"

namespace sm::test {

// {fb, ratio[4:0], agree_ok, matched, lr_ok, border_en, fail, off[5:0], d}, dw = clog2(DISP)
inline uint32_t pack_fields(const OutFields& f, int dw) {
  uint32_t v = f.fb;
  v = v << 5 | f.ratio;
  v = v << 1 | f.agree_ok;
  v = v << 1 | f.matched;
  v = v << 1 | f.lr_ok;
  v = v << 1 | f.border_en;
  v = v << 1 | f.fail;
  v = v << 6 | (static_cast<uint32_t>(f.off) & 63u);
  return v << dw | f.d;
}

// {tex_t, uniq_t, agree_t, lr_t, occ_t, tex_en, uniq_en, agree_en, lr_en, fill_bg, occ_en,
// subpix_fit, subpix[1:0]} with subpix = 0 (off), 1 (WTA fraction), 2 (WTA band)
inline uint64_t pack_cfg(const OutputRegs& r) {
  uint64_t v = r.tex_t;
  v = v << 8 | r.uniq_t;
  v = v << 8 | r.agree_t;
  v = v << 8 | r.lr_t;
  v = v << 8 | r.occ_t;
  v = v << 1 | r.tex_en;
  v = v << 1 | r.uniq_en;
  v = v << 1 | r.agree_en;
  v = v << 1 | r.lr_en;
  v = v << 1 | r.fill_bg;
  v = v << 1 | r.occ_en;
  v = v << 1 | r.subpix_fit;
  return v << 2 | (r.subpix_en ? r.subpix_src : 0u);
}

}  // namespace sm::test
