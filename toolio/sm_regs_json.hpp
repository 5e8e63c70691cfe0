// The register file of the tools (stereo_model --regs, stereo_sim --regs / --regs-at):
// one JSON object whose keys are the run-time registers of the generated register map
// (rtl/regmap.json) in lower case, with the map's ranges, plus the compile-time
// parameters (HwConfig field names) and a calibration file:
//
//   width height gain_l gain_r offset_l offset_r rect_enable occ filter_enable occ_edge edge_t
//   obj_near obj_tol obj_min_pixels   integers, the register's range (MIN_WIDTH etc.
//                                     evaluated at the configuration)
//   sw_table0 sw_table1               the SW_TABLE words (0..0xFFFFFFFF), or
//   sw_table                          an array of 1..32 weight codes 0..3 (the rest 0)
//   calib                             calibration JSON (sm_calibrate, model/calib_file.hpp);
//                                     a relative path is relative to the register file
//   max_width max_height disp census sw rect_radius cost_shift max_objects label_slots
//   band_k
//                                     compile-time parameters (HwConfig)
//
// Any other key, a value of the wrong type or out of range is a ToolError naming the
// file and the key.
#pragma once

#include <string>
#include <vector>

#include "sm_types.hpp"

namespace sm::tools {

struct RegsFile {
  std::vector<std::string> keys;  // keys the file sets, in file order
  std::string calib;              // the "calib" key as a path (resolved), empty if absent
  bool has(const std::string& key) const;
};

// Applies the file at `path` on top of hw and r: compile-time keys first (they set the
// ranges of the registers), then the registers. r.grid_l / r.grid_r are not touched (the
// caller applies `calib` once the active size is known). Throws ToolError.
RegsFile apply_regs_json(const std::string& path, HwConfig& hw, Regs& r);

}  // namespace sm::tools
