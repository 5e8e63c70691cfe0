// The compile-time configuration of the Verilated model this program links against:
// the SM_P_<NAME> definitions that sm_verilated() sets from the Verilog parameters it
// overrides. For sm_top, a parameter left at its Verilog default keeps HwConfig's
// default, which test_regmap checks against sm_top.v's parameter list, so no field of
// HwConfig can silently differ from the RTL this program simulates. A block test gets
// the fields of the parameters its block has (the others are HwConfig's defaults).
#pragma once

#include "sm_types.hpp"

namespace sm {

inline HwConfig verilated_config() {
  HwConfig hw;
#ifdef SM_P_MAX_WIDTH
  hw.max_width = SM_P_MAX_WIDTH;
#endif
#ifdef SM_P_MAX_HEIGHT
  hw.max_height = SM_P_MAX_HEIGHT;
#endif
#ifdef SM_P_DISP
  hw.disp = SM_P_DISP;
#endif
#ifdef SM_P_CENSUS
  hw.census = SM_P_CENSUS;
#endif
#ifdef SM_P_SW
  hw.sw = SM_P_SW;
#endif
#ifdef SM_P_RECT_RADIUS
  hw.rect_radius = SM_P_RECT_RADIUS;
#endif
#ifdef SM_P_COST_SHIFT
  hw.cost_shift = SM_P_COST_SHIFT;
#endif
#ifdef SM_P_AD_SHIFT
  hw.ad_shift = SM_P_AD_SHIFT;
#endif
#ifdef SM_P_AD_MAX
  hw.ad_max = SM_P_AD_MAX;
#endif
#ifdef SM_P_MAX_OBJECTS
  hw.max_objects = SM_P_MAX_OBJECTS;
#endif
#ifdef SM_P_LABEL_SLOTS
  hw.label_slots = SM_P_LABEL_SLOTS;
#endif
#ifdef SM_P_BAND_K
  hw.band_k = SM_P_BAND_K;
#endif
#ifdef SM_P_PU
  hw.pu = SM_P_PU;
#endif
#ifdef SM_P_SPECKLE_ROWS
  hw.speckle_rows = SM_P_SPECKLE_ROWS;
#endif
#ifdef SM_P_SPECKLE_LABELS
  hw.speckle_labels = SM_P_SPECKLE_LABELS;
#endif
  return hw;
}

}  // namespace sm
