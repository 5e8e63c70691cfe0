// stereo_sim's check: every frame's disparity and object packet from the RTL against the
// reference model (model/, run_pipeline) on the same frame and registers.
#pragma once

#include <string>
#include <vector>

#include "pipeline.hpp"
#include "sm_sim.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_regplan.hpp"

namespace sm::simapp {

struct ModelCheck {
  bool done = false;  // false: --no-check
  int mismatches = 0;
  std::string first_mismatch;
  std::vector<int> frame_mismatches;  // per frame (zeros without a check)
  std::vector<PipelineResult> model;  // per frame (empty without a check)
};

ModelCheck check_against_model(bool no_check, const HwConfig& hw, const SimInput& in, const RegisterPlan& plan,
                               const SimResult& res);

}  // namespace sm::simapp
