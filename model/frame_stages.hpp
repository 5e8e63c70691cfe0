// The pipeline recomposed from the whole-frame stage functions (the ones the RTL block
// tests compare against), in run_pipeline's stage order and with its registers. The
// benchmark and the unit tests check that run_pipeline, which streams rows through the
// same kernels, gives the same bits; a stage added to run_pipeline belongs here too
// (tests/test_pipeline_model.cpp fails until it is).
#pragma once

#include "pipeline.hpp"

namespace sm {

// Like run_pipeline(left, right, hw, regs, true, threads) (volumes kept, stage_ms empty).
PipelineResult run_frame_stages(const Image8& left, const Image8& right, const HwConfig& hw, const Regs& regs,
                                int threads = 1);

}  // namespace sm
