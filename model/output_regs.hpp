// The output stage's settings (sub-pixel estimator, validity rules; docs/algorithm.md
// section 9) as the model's functions take them. The registers SUBPIX .. SMOOTH_T of
// rtl/regmap.json (members of Regs) give them (output_regs); the studies also set the
// model-only estimator subpix_src 0, which no register reaches. The member defaults are
// the registers' reset values, chosen on the 14 scenes.
#pragma once

#include <cstdint>

#include "sm_types.hpp"

namespace sm {

struct OutputRegs {
  // ---- sub-pixel estimator (SUBPIX_CTRL) ----
  uint8_t subpix_en = 1;   // 0: fraction always 0
  uint8_t subpix_src = 2;  // 0: costs at the DP's level (a cost or fraction per (x, level) stored)
                           // 1: the WTA level's fraction, when the DP level is within 1 of it
                           // 2: the WTA band (A at WTA-2..WTA+2 stored per pixel), fitted at the DP level
  uint8_t subpix_fit = 0;  // 0: parabola, 1: equiangular (V) fit
  // ---- validity (VALID_CTRL); a failing enabled rule clears the valid bit ----
  uint8_t occ_en = 1;   // unmatched by the trellis (occluded) where the matches around its run
                        // differ by more than occ_t, or x < d (left border): invalid
  uint8_t occ_t = 1;    // 1: the single-level steps of slanted surfaces stay valid (filled)
  uint8_t fill_bg = 1;  // occ_en = 0: unmatched pixels take the background fill (min of the
                        // left match and every match right of them), never nearer than the
                        // DP's fill; 0: the DP's fill (left of the first match: disp(first))
  uint8_t lr_en = 1;    // left-right: invalid when |d_dp - right WTA of pixel x - d_dp| > lr_t
  uint8_t lr_t = 2;
  uint8_t agree_en = 1;  // DP/WTA agreement: invalid when |d_dp - d_wta| > agree_t
  uint8_t agree_t = 2;
  uint8_t uniq_en = 0;  // uniqueness: invalid when C2 - C1 < uniq_t (WTA curve)
  uint8_t uniq_t = 1;
  uint8_t tex_en = 0;  // texture: invalid when Cmax - C1 < tex_t (flat cost curve)
  uint8_t tex_t = 0;
  // ---- smoothing of the Q.4 value (SMOOTH_EN, SMOOTH_T; model/smooth.hpp) ----
  uint8_t smooth_en = 1;
  uint8_t smooth_t = 24;
};

// The same registers with every validity rule off and the DP's own fill: the dense mode
// (every pixel valid, the integer part = PipelineResult::post).
inline OutputRegs dense_mode(OutputRegs r) {
  r.occ_en = r.lr_en = r.uniq_en = r.agree_en = r.tex_en = 0;
  r.fill_bg = 0;
  return r;
}

// The settings the registers of r give: SUBPIX 0 = no fraction, 1 / 2 = estimator 1 / 2.
inline OutputRegs output_regs(const Regs& r) {
  OutputRegs o;
  o.subpix_en = r.subpix != 0;
  o.subpix_src = r.subpix != 0 ? r.subpix : 2;
  o.subpix_fit = r.subpix_fit;
  o.occ_en = r.occ_en;
  o.occ_t = r.occ_t;
  o.fill_bg = r.fill_bg;
  o.lr_en = r.lr_en;
  o.lr_t = r.lr_t;
  o.agree_en = r.agree_en;
  o.agree_t = r.agree_t;
  o.uniq_en = r.uniq_en;
  o.uniq_t = r.uniq_t;
  o.tex_en = r.tex_en;
  o.tex_t = r.tex_t;
  o.smooth_en = r.smooth_en;
  o.smooth_t = r.smooth_t;
  return o;
}

// The registers that give o (the inverse of output_regs for the estimators 1 and 2).
inline void set_output_regs(Regs& r, const OutputRegs& o) {
  r.subpix = o.subpix_en ? o.subpix_src : 0;
  r.subpix_fit = o.subpix_fit;
  r.occ_en = o.occ_en;
  r.occ_t = o.occ_t;
  r.fill_bg = o.fill_bg;
  r.lr_en = o.lr_en;
  r.lr_t = o.lr_t;
  r.agree_en = o.agree_en;
  r.agree_t = o.agree_t;
  r.uniq_en = o.uniq_en;
  r.uniq_t = o.uniq_t;
  r.tex_en = o.tex_en;
  r.tex_t = o.tex_t;
  r.smooth_en = o.smooth_en;
  r.smooth_t = o.smooth_t;
}

}  // namespace sm
