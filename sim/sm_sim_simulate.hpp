// stereo_sim's simulation stage: the camera's timing, the host's register writes and the
// wave window, handed to the Verilated model (RunFn) for one run over every frame.
#pragma once

#include <vector>

#include "sm_host.hpp"
#include "sm_sim.hpp"
#include "sm_sim_check.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_options.hpp"
#include "sm_sim_regplan.hpp"
#include "stereo_sim_app.hpp"

namespace sm::simapp {

struct SimRun {
  bool ran = false;                 // false: it only listed the traced scopes (--wave-scopes)
  std::vector<FrameHostPlan> host;  // per frame: what the host changed
  CameraTiming timing;
  int fold = 1;  // clocks per pixel of the datapath (DISP / PU)
  RunResult out;
  ModelCheck check;  // every frame against the model, as it left the RTL
  OutImage last;     // the last frame's output words
};

// Streams the input's frames through the model, each checked against the reference
// model (and written with --disp-each-frame) as it leaves the RTL. Throws on a wave
// window or core clock the input and camera do not allow.
SimRun simulate(const SimOptions& opt, const HwConfig& hw, SimInput& in, const RegisterPlan& plan,
                const RunFn& run_model);

}  // namespace sm::simapp
