// Validity rules of the output stage (docs/algorithm.md section 9.2), each with its own
// enable and threshold in OutputRegs.
#pragma once

#include <cstdlib>

#include "evidence.hpp"
#include "output_regs.hpp"

namespace sm {

// Which rules clear the valid bit of pixel (x, y) whose output level is d_out.
enum ValidFail : unsigned { kFailOcc = 1, kFailBorder = 2, kFailUniq = 4, kFailAgree = 8, kFailTex = 16, kFailLr = 32 };
// Every rule that fails, enabled or not (bit set = fails).
inline unsigned valid_failures(const Evidence& ev, int x, int y, int d_out, const OutputRegs& r) {
  unsigned f = 0;
  if (!ev.matched.at(x, y) && ev.gap.at(x, y) > r.occ_t) f |= kFailOcc;
  if (x < d_out) f |= kFailBorder;
  if (ev.c2.at(x, y) - ev.c1.at(x, y) < r.uniq_t) f |= kFailUniq;
  if (std::abs(static_cast<int>(ev.d.at(x, y)) - ev.dw.at(x, y)) > r.agree_t) f |= kFailAgree;
  if (ev.cmax.at(x, y) - ev.c1.at(x, y) < r.tex_t) f |= kFailTex;
  if (std::abs(static_cast<int>(ev.lr.at(x, y)) - ev.d.at(x, y)) > r.lr_t) f |= kFailLr;
  return f;
}
// The rules the registers enable (occ_en covers kFailOcc and kFailBorder).
inline unsigned enabled_rules(const OutputRegs& r) {
  return (r.occ_en ? kFailOcc | kFailBorder : 0u) | (r.uniq_en ? kFailUniq : 0u) | (r.agree_en ? kFailAgree : 0u) |
         (r.tex_en ? kFailTex : 0u) | (r.lr_en ? kFailLr : 0u);
}
// The valid bit: no enabled rule fails.
inline bool valid_pixel(const Evidence& ev, int x, int y, int d_out, const OutputRegs& r) {
  return (valid_failures(ev, x, y, d_out, r) & enabled_rules(r)) == 0;
}

// The failed rules other than the border in the 5 bits the output stage's fields carry them
// in ({lr, tex, agree, uniq, occ}: ValidFail without kFailBorder), and back to ValidFail
// bits with the border's (docs/algorithm.md 9.4).
inline unsigned fails_slot(unsigned f) { return (f & kFailOcc) | (f >> 1 & 0x1eu); }
inline unsigned fails_from_slot(unsigned slot, bool border) {
  return (slot & 1u) | (border ? kFailBorder : 0u) | (slot & 0x1eu) << 1;
}

}  // namespace sm
