// stereo_sim's pictures: the last frame's disparity in grey and colour, and the panel
// (inputs, rectified views, disparity, objects, error map and ground truth).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sm_sim_check.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_regplan.hpp"
#include "toolio/sm_outputs.hpp"

namespace sm::simapp {

// The pictures are staged in `outs` (written when it is committed).
// <dir>/disparity.png (grey) and <dir>/disparity_color.png of `disp` (float disparity).
void write_disparity_pictures(tools::OutputSet& outs, const std::string& dir, const cv::Mat& disp, const HwConfig& hw);

// <dir>/panel.png of the last frame: left, right / rectified left, rectified right /
// disparity, objects (the RTL's packet, else the model's) / error map, ground truth when
// there is one. `bad1`: the error map's figure (with ground truth).
void write_panel(tools::OutputSet& outs, const std::string& dir, const HwConfig& hw, const SimInput& in,
                 const RegisterPlan& plan, const ModelCheck& check, const std::vector<ObjectPacket>& packets,
                 const cv::Mat& disp, double bad1);

}  // namespace sm::simapp
