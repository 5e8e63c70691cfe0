#include "sm_types.hpp"

#include <fmt/format.h>

#include <cctype>

#include "sm_regmap.hpp"  // generated from rtl/regmap.json: the SW_TABLE reset values
#include "lower_case.hpp"

namespace sm {

int HwConfig::cost_bits() const { return clog2((census_bits() >> cost_shift) + 1); }

namespace {
struct Param {
  const char* name;  // sm_top parameter
  int HwConfig::*member;
};
constexpr Param kParams[] = {{"MAX_WIDTH", &HwConfig::max_width},
                             {"MAX_HEIGHT", &HwConfig::max_height},
                             {"DISP", &HwConfig::disp},
                             {"CENSUS", &HwConfig::census},
                             {"SW", &HwConfig::sw},
                             {"RECT_RADIUS", &HwConfig::rect_radius},
                             {"COST_SHIFT", &HwConfig::cost_shift},
                             {"AD_SHIFT", &HwConfig::ad_shift},
                             {"AD_MAX", &HwConfig::ad_max},
                             {"MAX_OBJECTS", &HwConfig::max_objects},
                             {"LABEL_SLOTS", &HwConfig::label_slots},
                             {"BAND_K", &HwConfig::band_k},
                             {"PU", &HwConfig::pu},
                             {"SPECKLE_ROWS", &HwConfig::speckle_rows},
                             {"SPECKLE_LABELS", &HwConfig::speckle_labels}};
}  // namespace

int* HwConfig::field(const std::string& name) {
  for (const Param& p : kParams)
    if (name == p.name) return &(this->*p.member);
  return nullptr;
}

const int* HwConfig::field(const std::string& name) const { return const_cast<HwConfig*>(this)->field(name); }

std::map<std::string, int> HwConfig::parameters() const {
  std::map<std::string, int> m;
  for (const Param& p : kParams) m[p.name] = this->*p.member;
  return m;
}

int HwConfig::flush_rows() const {  // as sm_top.v's FLUSH_ROWS
  return base_flush_rows() + (speckle_rows ? speckle_rows + (defs::kSpeckleSlack + 1 + 15) / 16 : 0);
}

int HwConfig::base_flush_rows() const {
  return (rect_radius + 1) + (census - 1) / 2 + (sw - 1) / 2 + 2 + band_k + 5 + 2 +
         (disp / 2 + 64 + 1 + 7 + 17 + 15) / 16 + 1;
}

void HwConfig::validate() const {
  auto bad = [](const std::string& m) { throw std::invalid_argument(m); };
  const auto params = parameters();
  for (const auto& l : defs::kLimits) {
    const int v = params.at(l.name);
    const std::string name = lower_case(l.name);  // the HwConfig field (and tool option)
    const bool parity_ok = l.parity == defs::Parity::kAny || (v % 2 == 0) == (l.parity == defs::Parity::kEven);
    if (v < l.min || v > l.max || !parity_ok)
      bad(fmt::format("{} {} must be {}{}..{} ({})", name, v,
                      l.parity == defs::Parity::kAny    ? ""
                      : l.parity == defs::Parity::kEven ? "even, "
                                                        : "odd, ",
                      l.min, l.max, l.desc));
  }
  if (max_width < min_width())
    bad(fmt::format("max_width {} below DISP/2 + 3 = {} (disp {})", max_width, min_width(), disp));
  if (label_slots < max_objects) bad(fmt::format("label_slots {} below max_objects {}", label_slots, max_objects));
  // sm_objects' g_bad_scan: its end-of-frame scan must fit the 256 clocks of a 16x16 frame
  const int scan = label_slots + max_objects * (clog2(disp) + 1) + 2;
  if (scan > 256)
    bad(
        fmt::format("label_slots {}: the object labeller's end-of-frame scan, label_slots + max_objects "
                    "(log2 disp + 1) + 2 = {} clocks, must fit a 16x16 frame's 256: at most {} labels here",
                    label_slots, scan, label_slots - (scan - 256)));
  if (pu != 0 && pu != disp && (pu < 2 || pu % 2 || disp % pu))
    bad(fmt::format("pu {} must be 0 (= disp), disp, or an even divisor of disp {}", pu, disp));
  // sm_top's pipeline depth in rows of 16 beats must stay below the 4-frame parameter
  // history (its g_bad_flush check, docs/algorithm.md "Per-frame parameters").
  if (base_flush_rows() >= 64)
    bad(
        fmt::format("pipeline of {} narrow rows (FLUSH_ROWS) outlasts the 4-frame parameter history: lower "
                    "rect_radius, band_k or disp",
                    base_flush_rows()));
  if (min_height() > max_height)
    bad(fmt::format("max_height {} below the shortest frame the pipeline allows, {} (speckle_rows {})", max_height,
                    min_height(), speckle_rows));
}

RectGrid RectGrid::identity(int width, int height) {
  RectGrid g;
  g.gw = points_w(width);
  g.gh = points_h(height);
  g.sx.resize(static_cast<size_t>(g.gw) * g.gh);
  g.sy.resize(g.sx.size());
  for (int gy = 0; gy < g.gh; ++gy)
    for (int gx = 0; gx < g.gw; ++gx) {
      g.sx[static_cast<size_t>(gy) * g.gw + gx] = static_cast<int16_t>((gx * kGridStep) << kMapFrac);
      g.sy[static_cast<size_t>(gy) * g.gw + gx] = static_cast<int16_t>((gy * kGridStep) << kMapFrac);
    }
  return g;
}

Regs Regs::defaults(const HwConfig& hw) {
  Regs r;
  r.set_reset_values(hw);
  set_sw_table_word(r, 0, static_cast<uint32_t>(regmap::kSW_TABLE0_CODES_RESET));
  set_sw_table_word(r, 1, static_cast<uint32_t>(regmap::kSW_TABLE1_CODES_RESET));
  r.grid_l = RectGrid::identity(r.width, r.height);
  r.grid_r = r.grid_l;
  return r;
}

uint32_t sw_table_word(const Regs& r, int half) {
  uint32_t w = 0;
  for (int k = 0; k < 16; ++k)
    w |= static_cast<uint32_t>(r.sw_table[static_cast<size_t>(16 * half + k)] & 3u) << (2 * k);
  return w;
}

void set_sw_table_word(Regs& r, int half, uint32_t word) {
  for (int k = 0; k < 16; ++k)
    r.sw_table[static_cast<size_t>(16 * half + k)] = static_cast<uint8_t>((word >> (2 * k)) & 3u);
}

}  // namespace sm
