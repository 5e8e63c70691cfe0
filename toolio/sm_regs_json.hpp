// The register file of the tools (stereo_model --regs, stereo_sim --regs / --regs-at):
// one JSON object whose keys are the run-time registers of the generated register map
// (rtl/regmap.json) in lower case, with the map's ranges, plus the compile-time
// parameters (HwConfig field names) and a calibration file:
//
//   <register>                        every value register of the map (value_registers():
//                                     width, gain_l, occ_edge, ...; docs/registers.md),
//                                     an integer in the register's range (MIN_WIDTH etc.
//                                     evaluated at the configuration)
//   sw_table0 sw_table1               the SW_TABLE words (0..0xFFFFFFFF), or
//   sw_table                          an array of 1..32 weight codes 0..3 (the rest 0)
//   calib                             calibration JSON (sm_calibrate, model/calib_file.hpp);
//                                     a relative path is relative to the register file
//   max_width max_height disp ...     compile-time parameters (HwConfig), in the ranges of
//                                     rtl/defs.json
//
// Any other key, a value of the wrong type or out of range is a ToolError naming the
// file and the key ("<file>: '<key>' = <value> is outside <lo>..<hi>" for a range).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
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

// The resets of hw that depend on the configuration (sm::set_config_resets), for a tool
// that changes the configuration after applying the file f to r: every value register f
// sets keeps the file's value.
void set_config_resets_keeping(const RegsFile& f, const HwConfig& hw, Regs& r);

// The value registers a tool sets (rtl/regmap.json: every register whose fields are all
// rw and shadowed, CONTROL aside; SW_TABLE0/1 are words of 16 weight codes), by address.
struct ValueRegister {
  std::string name;  // the map's name, e.g. "OCC_EDGE"
  const char* desc;  // the map's description
  uint32_t addr;
};
std::vector<ValueRegister> value_registers();
// The register's value in r (the word a host writes, before sign extension).
int64_t register_value(const std::string& name, const Regs& r);
// The register's range at hw, lo..hi (rtl/regmap.json: the field's min/max, else its width).
std::pair<int64_t, int64_t> register_limits(const std::string& name, const HwConfig& hw);
// Sets the register in r; a value outside the map's range at hw is a ToolError
// "<what> = <value> is outside <lo>..<hi>" (the wording of every range error of the
// register file too, where <what> is "<file>: '<key>'").
void set_register(const std::string& name, int64_t v, const HwConfig& hw, Regs& r, const std::string& what);

}  // namespace sm::tools
