// What the flags of an object list mean and what to change (docs/algorithm.md section 8,
// docs/streams.md): one line per flag set in an object packet's header word, naming
// what was dropped and the register or build parameter that helps. For every tool that
// reports object lists (stereo_model, the stereo_sim harness).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sm_types.hpp"

namespace sm::tools {

// Header word of an object packet (model object_packet, docs/streams.md): bit 8
// TOO-MANY, bit 9 TABLE-FULL, bit 10 LOST. Returns no line when none is set. hw and regs
// are the configuration and registers the list was made with (the values are quoted).
std::vector<std::string> object_flag_lines(uint32_t header, const HwConfig& hw, const Regs& regs);

}  // namespace sm::tools
