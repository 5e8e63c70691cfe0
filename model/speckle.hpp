// The speckle stage (docs/algorithm.md 9.8), rtl/sm_speckle.v: a connected region of valid
// pixels whose 4-neighbours' Q.4 values differ by at most `diff`, of at most `size` pixels,
// is a speckle (a mismatch island) and its pixels leave the stage invalid. A whole frame
// at hand would give OpenCV's filterSpeckles verdict; a streaming stage sees a pixel's
// region only up to ROWS rows below it, so it holds the words ROWS rows and keeps a pixel
// whose region may still grow (docs/evaluation.md, "Speckles").
//
// Labelling, in raster order: a valid pixel joins its left and upper neighbours of the
// same frame that are valid and within diff; it takes the root of the region it joins, a
// new label when it joins none, and when it joins two regions the root of the higher rank
// survives (the upper one's on a tie) and the other points to it (union by rank: a find
// follows at most log2(LABELS) pointers). Each label counts the undecided pixels stored
// with it and the labels pointing to it and is free again when that count falls to zero.
// Fresh labels come from a counter, then from a FIFO of freed ones. A pixel that finds no
// label free is labelled KEEP: it is kept, and so is every region that joins it.
//
// Verdict: right after the pixel entering at column x is labelled, the pixel ROWS rows
// above it (same column) leaves. It is kept when its region's root was reached on the
// entering row or the one above (the region may still grow), unless its frame has ended
// (the entering beat is virtual or of a later frame); else when its region holds more
// than `size` pixels (sizes saturate at kSpeckleSizeMax); else when it holds more than
// `trust` pixels and fewer than 1/16 of them fail the left-right check (confidence bit 7
// clear): a small object both views agree on, not a mismatch island. A cleared pixel
// leaves as the invalid word with the speckle bit (kOutSpeckle).
#pragma once

#include <cstdint>
#include <vector>

#include "outword.hpp"
#include "sm_types.hpp"

namespace sm {

constexpr uint32_t kOutSpeckle = 0x40000000u;  // invalid word's bit 30: cleared as a speckle
constexpr unsigned kSpeckleSizeMax = 8191;     // region sizes saturate here (13 bits)
constexpr unsigned kSpeckleTrustShift = 4;     // a trusted region: fewer than 1/2^4 of it fail left-right

// The stage's registers (SPECKLE_EN, SPECKLE_SIZE, SPECKLE_DIFF, SPECKLE_TRUST), latched at a frame's
// first beat; the defaults are their reset values (rtl/regmap.json).
struct SpeckleRegs {
  uint8_t en = RegValues{}.speckle_en;         // 0: every word leaves as it came (ROWS rows later)
  uint16_t size = RegValues{}.speckle_size;    // regions of at most size pixels are speckles (0..4095)
  uint8_t diff = RegValues{}.speckle_diff;     // Q.4 step between 4-neighbours that still joins them
  uint16_t trust = RegValues{}.speckle_trust;  // a region of more than trust pixels may be trusted (0..4095)
};

struct SpeckleStats {
  int peak_labels = 0;   // labels in use at once, most
  int longest_find = 0;  // pointers followed by one find, most
  long keep_pixels = 0;  // pixels labelled KEEP (no label was free)
  long trusted = 0;      // pixels kept only because their region is trusted (SPECKLE_TRUST)
};

// The stage one beat at a time, as the RTL takes them: side (defs::kSide* bits) and word
// in, the beat ROWS rows earlier out.
class SpeckleStage {
 public:
  SpeckleStage(int max_width, int rows, int labels);
  struct Beat {
    uint8_t side = 0;
    uint32_t word = 0;
  };
  Beat step(uint8_t side, uint32_t word, const SpeckleRegs& regs);
  const SpeckleStats& stats() const { return stats_; }

 private:
  struct RowMeta {  // what a stored row's beats leave with
    bool real = false, sof = false, en = false;
    uint8_t tag = 0, fid = 0;
    uint16_t size = 0, trust = 0;
  };
  void start_row(uint8_t side, const SpeckleRegs& regs);
  uint16_t label(uint32_t word, bool real);
  uint32_t verdict(uint16_t code, uint32_t word, const RowMeta& m, bool ended);
  uint16_t find(uint16_t l);
  uint16_t take_label(bool lr_bad);
  void add_pixel(uint16_t r, bool lr_bad);
  uint16_t merge(uint16_t a, uint16_t b);
  void release(uint16_t l);
  size_t at(int slot) const { return static_cast<size_t>(slot) * static_cast<size_t>(max_width_) + x_; }

  int max_width_, rows_, labels_;
  uint16_t none_, keep_;  // label codes past the table: invalid pixel, KEEP
  uint8_t row_mask_;      // row numbers modulo 2^RW, 2^RW > ROWS + 1
  // the ROWS + 1 rows of words and labels, and each row's meta
  std::vector<uint32_t> words_;
  std::vector<uint16_t> codes_;
  std::vector<RowMeta> meta_;
  // the label table
  std::vector<uint16_t> parent_, size_, bad_, refs_, fifo_;  // bad_: pixels failing left-right
  std::vector<uint8_t> rank_, last_;
  uint16_t fresh_ = 0, fifo_head_ = 0, fifo_count_ = 0;
  int in_use_ = 0;
  // position and the frame being labelled
  int slot_ = 0, x_ = 0;
  uint8_t row_ = 0, fid_ = 0, diff_ = 0, en_ = 0;  // en_, size_reg_, diff_: latched at SOF
  uint16_t size_reg_ = 0, trust_reg_ = 0;
  bool started_ = false;
  uint32_t left_word_ = 0;
  uint16_t left_code_ = 0;
  SpeckleStats stats_;
};

// The stage's registers in r (SPECKLE_EN, SPECKLE_SIZE, SPECKLE_DIFF, SPECKLE_TRUST).
inline SpeckleRegs speckle_regs(const Regs& r) {
  return {r.speckle_en, r.speckle_size, r.speckle_diff, r.speckle_trust};
}

// The words of a frame after the speckle stage of hw (unchanged when it has none).
OutImage speckle_words(const OutImage& in, const Regs& regs, const HwConfig& hw);

// One frame through a fresh stage, followed by ROWS virtual rows: the words it leaves with.
OutImage speckle_output(const OutImage& in, const SpeckleRegs& regs, int rows, int labels,
                        SpeckleStats* stats = nullptr);

}  // namespace sm
