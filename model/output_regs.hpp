// Planned registers of the output stage (sub-pixel estimator, validity rules, confidence;
// docs/algorithm.md section 9). Model-side only for now: the RTL that reads them comes
// later, and rtl/regmap.json may list only registers the RTL implements, so they live here
// (Regs::out) until then. Reset values = the defaults chosen on the 14 scenes.
#pragma once

#include <cstdint>

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
};

// The same registers with every validity rule off and the DP's own fill: the dense mode
// (every pixel valid, the integer part = PipelineResult::post).
inline OutputRegs dense_mode(OutputRegs r) {
  r.occ_en = r.lr_en = r.uniq_en = r.agree_en = r.tex_en = 0;
  r.fill_bg = 0;
  return r;
}

}  // namespace sm
