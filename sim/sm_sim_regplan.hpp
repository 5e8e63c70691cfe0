// stereo_sim's register plan: every frame's registers, from the defaults, --regs, --calib,
// the register options and the --regs-at schedule, planned before any input is read (a
// bad file simulates nothing).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "sm_host.hpp"
#include "sm_sim_options.hpp"
#include "sm_types.hpp"

namespace sm::simapp {

struct RegisterPlan {
  int width = 0, height = 0;                       // the active size (the options' or --regs')
  std::vector<Regs> regs;                          // per frame, validated
  std::vector<std::pair<int, std::string>> sched;  // --regs-at (frame, file), in frame order
  // A shard (--frame-range): regs hold frames first.. only, and host_report what the
  // host changed for them in the whole run's schedule (sm_sim_shards.hpp).
  size_t first = 0;
  std::vector<FrameHostPlan> host_report;
};

// Throws on a bad file, option or register value.
RegisterPlan plan_registers(const SimOptions& opt, const HwConfig& hw);

// Cuts the plan to the frames the input has; a --regs-at beyond them throws.
void fit_plan_to_input(RegisterPlan& plan, size_t nframes);

// What the host writes over AXI4-Lite while the camera streams, and per frame what it changed.
struct HostSchedule {
  std::vector<HostOp> ops;
  std::vector<FrameHostPlan> frames;
};
HostSchedule schedule_host_writes(const RegisterPlan& plan, const HwConfig& hw, bool late);

}  // namespace sm::simapp
