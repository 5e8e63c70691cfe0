// stereo_sim's check: every frame's disparity and object packet from the RTL against the
// reference model (model/, run_pipeline) on the same frame and registers. Frames are
// checked as they leave the RTL (check_frame), their object packets at the end
// (check_packets), so that no frame is held longer than it is in flight.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pipeline.hpp"
#include "sm_sim.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_regplan.hpp"

namespace sm::simapp {

struct ModelCheck {
  bool done = false;  // false: --no-check
  size_t first = 0;   // the run's first frame (frame numbers in messages are first + f)
  int mismatches = 0;
  std::string first_mismatch;
  std::vector<int> frame_mismatches;                // per frame (zeros without a check)
  std::vector<std::vector<uint32_t>> want_packets;  // per frame: the model's object packet
  std::optional<PipelineResult> last_model;         // the last frame's (empty without a check)
  StereoFrame last_input;                           // the last frame's input (for the panel)
};

ModelCheck start_check(bool no_check, size_t first, size_t nframes);

// Frame f of the run (its input and the RTL's disparity) against the model with regs.
void check_frame(ModelCheck& c, size_t f, const HwConfig& hw, const Regs& regs, const StereoFrame& in,
                 const OutImage& got);

// The RTL's object packets against the model's, once the run is over.
void check_packets(ModelCheck& c, const SimResult& res);

}  // namespace sm::simapp
