// The compile-time configuration of the Verilated sm_top this program links against:
// the SM_P_<NAME> definitions that sm_verilated() sets from the Verilog parameters.
#pragma once

#include "sm_types.hpp"

namespace sm {

inline HwConfig verilated_config() {
  HwConfig hw;
  hw.max_width = SM_P_MAX_WIDTH;
  hw.max_height = SM_P_MAX_HEIGHT;
  hw.disp = SM_P_DISP;
  hw.census = SM_P_CENSUS;
  hw.sw = SM_P_SW;
  hw.rect_radius = SM_P_RECT_RADIUS;
  return hw;
}

}  // namespace sm
