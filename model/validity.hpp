// Validity rules of the output stage (docs/algorithm.md section 9.2), each with its own
// enable and threshold in OutputRegs.
#pragma once

#include "evidence.hpp"
#include "output_regs.hpp"

namespace sm {

// Which rules clear the valid bit of pixel (x, y) whose output level is d_out.
enum ValidFail : unsigned { kFailOcc = 1, kFailBorder = 2, kFailUniq = 4, kFailAgree = 8, kFailTex = 16, kFailLr = 32 };
// Every rule that fails, enabled or not (bit set = fails).
unsigned valid_failures(const Evidence& ev, int x, int y, int d_out, const OutputRegs& r);
// The valid bit: no enabled rule fails (occ_en covers kFailOcc and kFailBorder).
bool valid_pixel(const Evidence& ev, int x, int y, int d_out, const OutputRegs& r);

}  // namespace sm
