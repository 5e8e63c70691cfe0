// Post-processing of the disparity stream (docs/algorithm.md, sections 7-8): the
// streak filters and the object separation (streaming connected-component labelling).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "sm_types.hpp"

namespace sm {

// ---- section 7: filters ------------------------------------------------------------

// Median over a (2*ry+1) x (2*rx+1) window of the sort keys (valid ? d + 1 : 0, with d
// the low clog2(DISP) bits). Window pixels outside the image take the centre's key.
// Result: key 0 -> 0x0000 (invalid), key k -> valid disparity k - 1.
DispImage post_median(const DispImage& in, const HwConfig& hw, int ry, int rx);
// The same window with the element of rank `rank` (0 = smallest key) instead of the
// middle one: rank 0 is a grey-level erosion, the median is rank N/2.
DispImage post_rank(const DispImage& in, const HwConfig& hw, int ry, int rx, int rank);

// The three filters of the post-processing chain, in chain order (chosen by measurement,
// see docs/algorithm.md section 7); sizes are rows x columns.
DispImage post_vmedian(const DispImage& in, const HwConfig& hw);   // filter 1: 5 x 1
DispImage post_median3(const DispImage& in, const HwConfig& hw);   // filter 2: 3 x 3
DispImage post_median53(const DispImage& in, const HwConfig& hw);  // filter 3: 5 x 3

// Recursive band filter F0 (issue 21 streak study, docs/evaluation.md "Streak study"; the
// chain's first step with k = hw.band_k, RTL sm_post_band): top to bottom, a = the output at (x, y-1), c = the input at
// (x, y), d(p) = the low clog2(DISP) bits. When a and c are valid, |d(c) - d(a)| > 1 and some
// input row y+j (1 <= j <= k, inside the frame) is valid with |d(in(x, y+j)) - d(a)| <= 1,
// the output is a (a band of at most k rows between rows that agree is replaced from
// above); otherwise it is c. Row 0 is c. Output words as the medians': 0x8000 | d when
// valid, 0x0000 when invalid (so DW + 1 bits per stored word are exact). k = 0: no change
// but that normalisation.
DispImage post_band(const DispImage& in, const HwConfig& hw, int k);

// A disabled filter's output: each word's valid bit and low clog2(DISP) bits, the rest
// zero. The filters keep only these bits of a word (the core's stream has zeros between
// them), so a disabled filter passes the core's words unchanged.
DispImage post_bypass(const DispImage& in, const HwConfig& hw);

// The chain F0 (post_band with k = hw.band_k, bit 3 of regs.filter_enable), then F1..F3
// (bits 0..2); a disabled filter is post_bypass. `steps` (optional) receives
// the image after each of the four steps, F0 first. threads: each filter on that many
// bands of rows (F0: of columns), same result for any count.
DispImage post_process(const DispImage& in, const Regs& regs, const HwConfig& hw,
                       std::vector<DispImage>* steps = nullptr, int threads = 1);

// ---- section 8: objects ------------------------------------------------------------

struct Object {
  uint16_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // bounding box, inclusive
  uint32_t count = 0;                       // pixels
  uint32_t sum_disp = 0;                    // sum of their disparities
  uint8_t mean_disp = 0;                    // floor(sum_disp / count)
  uint8_t max_disp = 0;                     // nearest disparity
  bool operator==(const Object& o) const {
    return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1 && count == o.count && sum_disp == o.sum_disp &&
           mean_disp == o.mean_disp && max_disp == o.max_disp;
  }
};

struct ObjectList {
  std::vector<Object> objects;    // at most hw.max_objects, in label order
  bool too_many_objects = false;  // more components of >= obj_min_pixels than listed
  bool table_full = false;        // a pixel found no free label: it was dropped (background)
  // Diagnostics of the label table (not in the packet): labels allocated in the frame (what
  // a table without recycling would need) and the most busy at once (what LABEL_SLOTS must hold).
  int labels_started = 0;
  int labels_peak = 0;
};

// One-pass labelling of the near pixels (valid, d >= regs.obj_near; an invalid pixel never
// is), 4-connected, neighbours merging when |d1 - d2| <= regs.obj_tol, with hw.label_slots
// labels that are recycled within the frame (absorbed labels, and components that ended
// below regs.obj_min_pixels, once no pixel still to come can name them).
ObjectList separate_objects(const DispImage& in, const Regs& regs, const HwConfig& hw);

// separate_objects one row at a time (the rows in order, each w pixels; then finish): the
// same list. run_pipeline labels rows while other threads still make output words.
class ObjectLabeller {
 public:
  ObjectLabeller(int w, const Regs& regs, const HwConfig& hw);
  ~ObjectLabeller();
  void row(const DispPix* px, int y);
  ObjectList finish();

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// The AXI4-Stream packet of one object list (section 8): a header word, then five words
// per object. `lost` = the packet of an earlier list was dropped since the last one sent.
std::vector<uint32_t> object_packet(const ObjectList& list, bool lost);

}  // namespace sm
