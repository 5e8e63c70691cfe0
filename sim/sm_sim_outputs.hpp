// stereo_sim's lossless disparity files (--disp-file, --disp-each-frame).
#pragma once

#include <opencv2/core.hpp>

#include "sm_sim.hpp"
#include "sm_sim_options.hpp"
#include "toolio/sm_outputs.hpp"

namespace sm::simapp {

// opt.disp_file of the last frame's `disp` (float disparity) and, with
// --disp-each-frame, <stem>_NNN<ext> of every frame of `res`, staged in `outs`.
void write_disparity_files(tools::OutputSet& outs, const SimOptions& opt, const SimResult& res, const cv::Mat& disp);

}  // namespace sm::simapp
