// Shared types of the reference model. Every stage of the RTL has one function in
// the model (see docs/algorithm.md); these are the containers they exchange and the
// two parameter sets: HwConfig (compile-time parameters of the RTL) and Regs
// (run-time registers written over AXI4-Lite).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "sm_defs.hpp"  // generated from rtl/defs.json

namespace sm {

// ceil(log2(v)) for v >= 1, as Verilog's $clog2: the RTL's derived widths.
constexpr int clog2(long v) {
  int n = 0;
  while ((1L << n) < v) ++n;
  return n;
}

// A W x H plane of one integer type, row-major.
template <typename T>
struct Plane {
  int w = 0;
  int h = 0;
  std::vector<T> px;
  Plane() = default;
  Plane(int w_, int h_, T fill = T{}) : w(w_), h(h_), px(static_cast<size_t>(w_) * h_, fill) {}
  T& at(int x, int y) { return px[static_cast<size_t>(y) * w + x]; }
  const T& at(int x, int y) const { return px[static_cast<size_t>(y) * w + x]; }
  bool operator==(const Plane& o) const { return w == o.w && h == o.h && px == o.px; }
  bool operator!=(const Plane& o) const { return !(*this == o); }
};

using Image8 = Plane<uint8_t>;

// Census vector of up to 256 bits (15x15 window -> 224 bits). Bit k is the k-th
// neighbour in raster order of the window with the centre skipped (docs/algorithm.md).
using CensusVec = std::array<uint64_t, 4>;
using CensusImage = Plane<CensusVec>;

// A W x H x D volume, d fastest: index (y * w + x) * d_levels + d.
template <typename T>
struct Volume {
  int w = 0;
  int h = 0;
  int d = 0;
  std::vector<T> v;
  Volume() = default;
  Volume(int w_, int h_, int d_, T fill = T{}) : w(w_), h(h_), d(d_), v(static_cast<size_t>(w_) * h_ * d_, fill) {}
  T& at(int x, int y, int k) { return v[(static_cast<size_t>(y) * w + x) * d + k]; }
  const T& at(int x, int y, int k) const { return v[(static_cast<size_t>(y) * w + x) * d + k]; }
  T* pix(int x, int y) { return &v[(static_cast<size_t>(y) * w + x) * d]; }
  const T* pix(int x, int y) const { return &v[(static_cast<size_t>(y) * w + x) * d]; }
  bool operator==(const Volume& o) const { return w == o.w && h == o.h && d == o.d && v == o.v; }
};

using CostVolume = Volume<uint8_t>;

// Disparity pixel as it travels on the disparity stream: bit 15 = valid, low bits =
// disparity (0..DISP-1). Same encoding as m_axis_tdata of the IP.
using DispPix = uint16_t;
constexpr DispPix kDispValid = 0x8000;
using DispImage = Plane<DispPix>;
inline DispPix make_disp(unsigned d, bool valid) {
  return static_cast<DispPix>((valid ? kDispValid : 0) | (d & 0x7fff));
}
inline unsigned disp_value(DispPix p) { return p & 0x7fffu; }
inline bool disp_valid(DispPix p) { return (p & kDispValid) != 0; }

// Compile-time parameters of the RTL (Verilog parameters of sm_top).
struct HwConfig {
  int max_width = 320;        // MAX_WIDTH: widest active line
  int max_height = 240;       // MAX_HEIGHT: tallest active frame
  int disp = 128;             // DISP: disparity levels 0..DISP-1
  int census = 15;            // CENSUS: census window side
  int sw = 5;                 // SW: support-weight window side
  int rect_radius = 18;       // RECT_RADIUS: rows above/below the output row the
                              // rectifier can read (line buffer holds 2R+2 rows)
  int cost_shift = 2;         // COST_SHIFT: raw Hamming cost >> COST_SHIFT feeds aggregation
  int ad_shift = 2;           // AD_SHIFT: the cost's intensity term is |left - right| >> AD_SHIFT ...
  int ad_max = 7;             // AD_MAX: ... capped at AD_MAX (0: census only; algorithm.md section 4)
  int max_objects = 8;        // MAX_OBJECTS (K): objects reported per frame
  int label_slots = 64;       // LABEL_SLOTS: equivalence-table entries of the labeller
  int band_k = 8;             // BAND_K: look-ahead rows of the band filter F0
  int pu = 0;                 // PU: disparity levels computed per clock (0 = DISP, fully parallel)
  int speckle_rows = 0;       // SPECKLE_ROWS: rows the speckle stage (9.8) holds a word; 0: no stage
  int speckle_labels = 1024;  // SPECKLE_LABELS: its label-table entries
  // Levels per clock and clocks per beat of the folded datapath (docs/algorithm.md,
  // "Folded datapath"): F = DISP / PU clocks per pixel in cost, aggregation and DP.
  int levels_per_clock() const { return pu ? pu : disp; }
  int clocks_per_beat() const { return disp / levels_per_clock(); }
  int census_bits() const { return census * census - 1; }
  // Narrowest active line: 16, or DISP/2 + 3 when larger -- the DP reads a line's
  // decisions back DISP/2 + 2 beats after its forward pass wrote them (sm_dp.v), so a
  // shorter line would overlap its own backward pass.
  int min_width() const { return disp / 2 + 3 > 16 ? disp / 2 + 3 : 16; }
  int cost_bits() const;  // width of the aggregated cost (see algorithm.md)
  // Virtual rows after a frame, sm_top's FLUSH_ROWS: the pipeline depth in rows of 16 beats,
  // the speckle stage's SPECKLE_ROWS rows and queue (kSpeckleSlack + 1 beats) included;
  // base_flush_rows() without them.
  int flush_rows() const;
  int base_flush_rows() const;
  // Shortest active frame: 16, or more when the pipeline is deeper than four 16-row
  // frames (the speckle stage): the 4-frame parameter history must outlast the pipeline.
  int min_height() const { return flush_rows() / 4 + 1 > 16 ? flush_rows() / 4 + 1 : 16; }
  // The checked mode's reset (rtl/regmap.json's SPECKLE_MODE and PIXEL_RULES): the speckle
  // mode where the stage is built (SPECKLE_EN on, LR_EN and AGREE_EN off), the per-pixel
  // left-right and agreement rules elsewhere (docs/evaluation.md, "Speckles").
  bool speckle_mode() const { return speckle_rows > 0; }
  bool pixel_rules() const { return !speckle_mode(); }

  // Throws std::invalid_argument on an illegal combination: every parameter inside its
  // range of defs::kLimits (rtl/defs.json, the ranges sm_top checks at elaboration), then
  // the rules between parameters.
  void validate() const;
  // Every field by its sm_top parameter name.
  std::map<std::string, int> parameters() const;
  // The field of an sm_top parameter name ("DISP" -> &disp), nullptr for any other name
  // (the one list of the names in C++; parameters() is built from it).
  int* field(const std::string& name);
  const int* field(const std::string& name) const;
};

// Rectification map as a coarse grid of source coordinates (docs/algorithm.md, stage 2).
constexpr int kGridShift = defs::kGridShift;  // grid spacing 16 output pixels
constexpr int kGridStep = 1 << kGridShift;
constexpr int kMapFrac = defs::kGridFrac;  // grid coordinates are Q.5 (1/32 px)
constexpr int kInterpFrac = 4;             // bilinear weights are 1/16
struct RectGrid {
  int gw = 0;               // grid points per row: ceil(W/16) + 1
  int gh = 0;               // grid rows: ceil(H/16) + 1
  std::vector<int16_t> sx;  // source x, Q.5, gw*gh entries, row-major
  std::vector<int16_t> sy;  // source y, Q.5
  static RectGrid identity(int width, int height);
  static int points_w(int width) { return defs::grid_pts(width); }
  static int points_h(int height) { return defs::grid_pts(height); }
};

}  // namespace sm

// sm::RegValues, generated from rtl/regmap.json: one member per value register (WIDTH,
// GAIN_L, OCC, ...) named after it in lower case, initialised to its reset value. It needs
// HwConfig above.
#include "sm_regvalues.hpp"

namespace sm {

// Run-time registers (AXI4-Lite), with the paper's defaults. The value registers are the
// generated base RegValues (a register added to rtl/regmap.json is a member here with no
// edit); the rest are kept here by hand.
struct Regs : RegValues {
  RectGrid grid_l;  // empty = identity for the active size
  RectGrid grid_r;
  // SW_TABLE0/1: 2-bit weight codes by |dI| >> 3 (all 0 here, the reset values of
  // regmap.json by defaults())
  std::array<uint8_t, 32> sw_table{};
  // The registers' reset values at hw (rtl/regmap.json: width = max_width, ...) and the
  // identity grids of that size.
  static Regs defaults(const HwConfig& hw);
};

// The checked mode's rules: the speckle mode (docs/algorithm.md 9.8: the stage on, the
// left-right and agreement rules it replaces off) or the per-pixel rules (the reverse).
inline void set_checked_rules(Regs& r, bool speckle) {
  r.speckle_en = speckle;
  r.lr_en = !speckle;
  r.agree_en = !speckle;
}

// The registers whose reset depends on the configuration beyond the active size
// (SPECKLE_EN, LR_EN, AGREE_EN: HwConfig::speckle_mode), set to their reset at hw: for a
// tool that changes the configuration after Regs::defaults.
inline void set_config_resets(const HwConfig& hw, Regs& r) { set_checked_rules(r, hw.speckle_mode()); }

// Word `half` (0 or 1) of the SW_TABLE0/SW_TABLE1 registers: the 16 two-bit codes
// sw_table[16 * half + k] in bits 2k+1:2k (the one packing of the table in C++).
uint32_t sw_table_word(const Regs& r, int half);
// The reverse: sets sw_table[16 * half .. 16 * half + 15] from the register word.
void set_sw_table_word(Regs& r, int half, uint32_t word);

}  // namespace sm
