// Writes a register set (sm::Regs) into the IP over AXI4-Lite, using the addresses
// generated from rtl/regmap.json, and applies a calibration file to a register set.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "calib_file.hpp"
#include "sm_axil.hpp"
#include "sm_regmap.hpp"
#include "sm_types.hpp"

namespace sm {

// The calibration's grids replace the identity grids; its size must be the active one.
inline void apply_calib(const CalibFile& c, Regs& regs) {
  if (c.width != regs.width || c.height != regs.height)
    throw std::runtime_error(
        fmt::format("calibration is for {}x{}, the active size is {}x{}", c.width, c.height, regs.width, regs.height));
  regs.grid_l = c.left;
  regs.grid_r = c.right;
  regs.rect_enable = true;
}

// One run-time register word as the host writes it.
struct RegWord {
  uint32_t addr;
  uint32_t value;
  const char* name;  // register name (rtl/regmap.json)
};

// Every run-time register of r as register words, in address order (CONTROL and the
// grids aside).
inline std::vector<RegWord> register_words(const Regs& r) {
  using namespace regmap;
  // the value registers (sm::Regs member of the register's name; a signed one sign-extends)
  std::vector<RegWord> w;
#define SM_X(NAME, member) w.push_back({k##NAME, static_cast<uint32_t>(static_cast<int32_t>(r.member)), #NAME});
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  w.push_back({kSW_TABLE0, sw_table_word(r, 0), "SW_TABLE0"});
  w.push_back({kSW_TABLE1, sw_table_word(r, 1), "SW_TABLE1"});
  std::sort(w.begin(), w.end(), [](const RegWord& a, const RegWord& b) { return a.addr < b.addr; });
  return w;
}

inline bool same_grid(const RectGrid& a, const RectGrid& b) {
  return a.gw == b.gw && a.gh == b.gh && a.sx == b.sx && a.sy == b.sy;
}

// The grid window writes of one camera's grid into `bank`: {address, word}.
inline std::vector<std::pair<uint32_t, uint32_t>> grid_words(const HwConfig& hw, int cam, int bank, const RectGrid& g) {
  std::vector<std::pair<uint32_t, uint32_t>> w;
  for (int gy = 0; gy < g.gh; ++gy)
    for (int gx = 0; gx < g.gw; ++gx) {
      // The point index is the rectifier's grid address {gy, gx} (model/calib_file.hpp).
      const uint32_t point = grid_waddr(hw, 0, gx, gy);
      w.emplace_back(regmap::grid_addr(cam, bank, static_cast<int>(point)), grid_wdata(g, gx, gy));
    }
  return w;
}

template <class Top>
void write_grid(AxilMaster<Top>& axil, const HwConfig& hw, int cam, int bank, const RectGrid& g) {
  for (const auto& [addr, word] : grid_words(hw, cam, bank, g))
    if (axil.write(addr, word) != 0) throw std::runtime_error(fmt::format("grid write to 0x{:x} refused", addr));
}

inline uint32_t control_word(int bank) {
  return (1u << regmap::kCONTROL_ENABLE_LSB) | (static_cast<uint32_t>(bank) << regmap::kCONTROL_GRID_BANK_LSB);
}

// Writes every run-time register; the grids go into `bank`, which CONTROL then selects.
// All of it takes effect at the next frame start.
template <class Top>
void write_registers(AxilMaster<Top>& axil, const Regs& r, const HwConfig& hw, int bank = 0) {
  for (const RegWord& w : register_words(r))
    if (axil.write(w.addr, w.value) != 0) throw std::runtime_error(fmt::format("register {} write refused", w.name));
  const RectGrid idl = RectGrid::identity(r.width, r.height);
  write_grid(axil, hw, 0, bank, r.grid_l.gw ? r.grid_l : idl);
  write_grid(axil, hw, 1, bank, r.grid_r.gw ? r.grid_r : idl);
  if (axil.write(regmap::kCONTROL, control_word(bank)) != 0) throw std::runtime_error("register CONTROL write refused");
}

}  // namespace sm
