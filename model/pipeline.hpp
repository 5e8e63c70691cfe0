// The whole reference pipeline: every stage of docs/algorithm.md in stream order,
// keeping each stage's output so tests and tools can compare any stage on its own.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "aggregate.hpp"
#include "census.hpp"
#include "dp.hpp"
#include "evidence.hpp"
#include "outword.hpp"
#include "post.hpp"
#include "pre.hpp"
#include "sm_types.hpp"

namespace sm {

struct PipelineResult {
  Image8 bl, br;                      // after brightness control
  Image8 rl, rr;                      // after rectification
  CostVolume raw;                     // matching costs H (kept when keep_volumes)
  CostVolume agg;                     // aggregated costs (kept when keep_volumes)
  DispImage dp;                       // trellis DP output
  DispImage post;                     // after the enabled post-processing filters
  std::vector<DispImage> post_steps;  // after each filter step F0..F3 (enabled or not)
  ObjectList objects;
  Evidence evidence;  // per-pixel evidence of the output stage (model/evidence.hpp)
  OutImage out;       // the output word per pixel, smoothed (model/outword.hpp, model/smooth.hpp)
  std::vector<std::pair<std::string, double>> stage_ms;  // wall time per stage
};

// Runs one frame. left/right must be regs.width x regs.height; throws
// std::invalid_argument otherwise. keep_volumes=false drops raw/agg to save memory.
// threads: census to DP run in that many bands of rows (model/parallel.hpp), with the
// same result for any count; stage_ms then sums the bands' times.
PipelineResult run_pipeline(const Image8& left, const Image8& right, const HwConfig& hw, const Regs& regs,
                            bool keep_volumes = true, int threads = 1);

// Checks run-time registers against the compile-time parameters; throws
// std::invalid_argument naming the field.
void validate_regs(const Regs& regs, const HwConfig& hw);

}  // namespace sm
