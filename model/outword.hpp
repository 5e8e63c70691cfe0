// The output word of the IP (docs/algorithm.md section 9.4):
//   valid:   m_axis_tdata[31:0] = {1, 7'b0, confidence[23:16], disparity_q12_4[15:0]}
//   invalid: m_axis_tdata[31:0] = {0, 0, fails[29:24], 24'b0}
// disparity_q12_4 = 16 d + f (d the integer level, f the Q.4 fraction); fails = the enabled
// validity rules that cleared the pixel (ValidFail bits, validity.hpp).
#pragma once

#include <cstdint>

#include "evidence.hpp"
#include "output_regs.hpp"
#include "sm_types.hpp"

namespace sm {

using OutImage = Plane<uint32_t>;
constexpr uint32_t kOutValid = 0x80000000u;
// The evidence byte's fields (docs/algorithm.md 9.3), the confidence of the words before the
// smoothing: |lr - d| <= 1, matched with x >= d_out, |d - dw| <= 1, and the ratio.
constexpr unsigned kConfLrOk = 0x80u, kConfMatched = 0x40u, kConfAgreeOk = 0x20u, kConfRatio = 0x1fu;
inline uint32_t make_out_word(bool valid, unsigned conf, unsigned q4, unsigned fails = 0) {
  return valid ? kOutValid | (conf & 0xffu) << 16 | (q4 & 0xffffu) : (fails & 0x3fu) << 24;
}
inline bool out_valid(uint32_t w) { return (w & kOutValid) != 0; }
inline unsigned out_conf(uint32_t w) { return (w >> 16) & 0xffu; }
inline unsigned out_q4(uint32_t w) { return w & 0xffffu; }
// The rules that cleared an invalid word (0 for a valid one).
inline unsigned out_fails(uint32_t w) { return out_valid(w) ? 0u : (w >> 24) & 0x3fu; }

// The output stage in the two halves the RTL has (docs/algorithm.md 9.6). At the DP's
// read-out a pixel's evidence becomes the fields below, which travel beside the disparity
// through the post filters; after them out_word forms the word from those fields and the
// filters' level.
struct OutFields {
  uint8_t d = 0;           // the DP's level (after its fill)
  int8_t off = 0;          // the Q.4 value at d minus 16 d (subpix_q4; -24..24)
  bool fail = false;       // an enabled rule other than the left border fails
  bool border_en = false;  // the left-border rule (x < d_out) is on (occ_en)
  bool lr_ok = false;      // confidence bit 7: |lr - d| <= 1
  bool matched = false;    // matched by the trellis (confidence bit 6 with x >= d_out)
  bool agree_ok = false;   // confidence bit 5: |d - dw| <= 1
  uint8_t ratio = 0;       // confidence bits 4:0; where fail, the rules that fail instead
                           // (fails_slot: an invalid pixel's confidence is 0, so the
                           // fields keep their width)
  uint8_t fb = 0;          // background fill level (unmatched, occ_en 0, fill_bg 1), else DISP - 1
};
// The fields of evidence pixel (x, y). nd = DISP.
OutFields out_fields(const Evidence& ev, int x, int y, int nd, const OutputRegs& r);
// The output level: the post filters' level, or the background fill where it is lower.
int out_level(const OutFields& f, DispPix p);
// The output word of a pixel at column x from its fields and the post filters' output p.
uint32_t out_word(const OutFields& f, DispPix p, int x, int nd);

// The output word of every pixel from the evidence and the post-processed disparity
// (post: the filters' output, same size): level d_out = post's (or the background fill for
// unmatched pixels when occ_en = 0 and fill_bg = 1), its Q.4 value (subpix_q4 at the DP's
// level, subpix_after_post), the validity rules and the confidence. nd = DISP.
// With threads > 1 the rows are split into bands (each pixel's word depends on its own
// evidence only: the same words for any thread count).
OutImage make_output(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int conf_variant = 0,
                     int threads = 1);
// make_output's rows y0..y1-1 into out (post's size; no size check): the same words.
void make_output_rows(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int conf_variant, int y0,
                      int y1, OutImage& out);

// What the object labeller reads of each output word (section 8): its valid bit and its
// level rounded to the nearest integer, (q4 + 8) >> 4 (invalid pixels: level 0, never
// an object).
DispImage object_levels(const OutImage& out);
// object_levels of rows y0..y1-1 into d (out's size).
void object_levels_rows(const OutImage& out, int y0, int y1, DispImage& d);

// Q.4 disparity as float pixels (negative = invalid), as disp_to_float for DispImage.
// (In tools: toolio's out_to_float.)

}  // namespace sm
