// Writes a register set (sm::Regs) into the IP over AXI4-Lite, using the addresses
// generated from rtl/regmap.json, and applies a calibration file to a register set.
#pragma once

#include <stdexcept>

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

template <class Top>
void write_grid(AxilMaster<Top>& axil, const HwConfig& hw, int cam, int bank, const RectGrid& g) {
  for (int gy = 0; gy < g.gh; ++gy)
    for (int gx = 0; gx < g.gw; ++gx) {
      // The point index is the rectifier's grid address {gy, gx} (model/calib_file.hpp).
      const uint32_t point = grid_waddr(hw, 0, gx, gy);
      const uint32_t addr = regmap::grid_addr(cam, bank, static_cast<int>(point));
      if (axil.write(addr, grid_wdata(g, gx, gy)) != 0)
        throw std::runtime_error(fmt::format("grid write to 0x{:x} refused", addr));
    }
}

// Writes every run-time register; the grids go into `bank`, which CONTROL then selects.
// All of it takes effect at the next frame start.
template <class Top>
void write_registers(AxilMaster<Top>& axil, const Regs& r, const HwConfig& hw, int bank = 0) {
  auto wr = [&](uint32_t addr, uint32_t v, const char* name) {
    if (axil.write(addr, v) != 0) throw std::runtime_error(fmt::format("register {} write refused", name));
  };
  using namespace regmap;
  wr(kWIDTH, static_cast<uint32_t>(r.width), "WIDTH");
  wr(kHEIGHT, static_cast<uint32_t>(r.height), "HEIGHT");
  wr(kGAIN_L, r.gain_l, "GAIN_L");
  wr(kGAIN_R, r.gain_r, "GAIN_R");
  wr(kOFFSET_L, static_cast<uint32_t>(static_cast<int32_t>(r.offset_l)), "OFFSET_L");
  wr(kOFFSET_R, static_cast<uint32_t>(static_cast<int32_t>(r.offset_r)), "OFFSET_R");
  wr(kRECT_ENABLE, r.rect_enable ? 1u : 0u, "RECT_ENABLE");
  wr(kOCC, r.occ, "OCC");
  uint64_t table = 0;
  for (int k = 0; k < 32; ++k) table |= static_cast<uint64_t>(r.sw_table[k] & 3u) << (2 * k);
  wr(kSW_TABLE0, static_cast<uint32_t>(table), "SW_TABLE0");
  wr(kSW_TABLE1, static_cast<uint32_t>(table >> 32), "SW_TABLE1");
  wr(kFILTER_ENABLE, r.filter_enable, "FILTER_ENABLE");
  wr(kOBJ_NEAR, r.obj_near, "OBJ_NEAR");
  wr(kOBJ_TOL, r.obj_tol, "OBJ_TOL");
  wr(kOBJ_MIN_PIXELS, r.obj_min_pixels, "OBJ_MIN_PIXELS");
  const RectGrid idl = RectGrid::identity(r.width, r.height);
  write_grid(axil, hw, 0, bank, r.grid_l.gw ? r.grid_l : idl);
  write_grid(axil, hw, 1, bank, r.grid_r.gw ? r.grid_r : idl);
  wr(kCONTROL, (1u << kCONTROL_ENABLE_LSB) | (static_cast<uint32_t>(bank) << kCONTROL_GRID_BANK_LSB), "CONTROL");
}

}  // namespace sm
