// The named configurations of the whole IP that the build makes (CMakeLists.txt's
// SM_PAPER_PARAMS, SM_ZYNQ_PARAMS, ...: stereo_sim, stereo_sim_zynq, the synthesis targets),
// for the tools and tests that model one of them. Generated from the same lists.
#pragma once

#include <string>
#include <vector>

#include "sm_types.hpp"

namespace sm {

// "paper", "zynq", "vga", "small", "small_fold".
std::vector<std::string> config_names();

// The HwConfig of the configuration `name` (its parameters set, the others at HwConfig{});
// throws std::invalid_argument for a name not in config_names().
HwConfig named_config(const std::string& name);

}  // namespace sm
