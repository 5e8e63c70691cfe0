// stereo_sim's pictures: the last frame's disparity as an 8-bit preview and in colour
// with its colour bar, and the panel (inputs, rectified views, disparity, objects, error
// map and ground truth, point cloud), drawn with toolio/sm_pictures.hpp.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib_file.hpp"
#include "sm_sim_check.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_regplan.hpp"
#include "toolio/sm_outputs.hpp"
#include "toolio/sm_pictures.hpp"

namespace sm::simapp {

// The colour range of every disparity picture of the run: the ground truth's range when
// the input has one (the scene's known disparities), else the data's.
tools::ColourRange picture_range(const SimInput& in, const cv::Mat& disp);

// The pictures are staged in `outs` (written when it is committed).
// <dir>/disparity.png (the 8-bit preview, tools::disp_to_grey: 0 = invalid, disparity 0 =
// grey 1) and <dir>/disparity_color.png (colour over `r` with the colour bar; depth ticks
// when `cam`) of `disp` (float disparity).
void write_disparity_pictures(tools::OutputSet& outs, const std::string& dir, const cv::Mat& disp, const HwConfig& hw,
                              tools::ColourRange r, const RectCamera* cam);

// What the panel shows of the last frame.
struct PanelData {
  const SimInput* in = nullptr;
  const StereoFrame* frame = nullptr;                  // the last frame's input (ModelCheck::last_input)
  const PipelineResult* model = nullptr;               // the last frame's (last_frame_model)
  const cv::Mat* disp = nullptr;                       // float disparity
  tools::ColourRange range;                            // picture_range()
  const std::vector<ObjectPacket>* packets = nullptr;  // the RTL's (empty: the model's objects)
  const RectCamera* cam = nullptr;                     // depth ticks and a point-cloud tile
  double cloud_max_depth = 0;                          // metres, 0: none
  double bad1 = 0;                                     // the error map's figure (with ground truth)
};

// <dir>/panel.png of the last frame, its tiles magnified by whole pixels to at least 240
// rows (a small configuration's frame): left, right / rectified left, rectified right /
// disparity with its colour bar, objects labelled #0, #1, ... with the frame's flags /
// error map with its legend, ground truth (with one) / the point cloud's bird's-eye view
// (with a camera).
void write_panel(tools::OutputSet& outs, const std::string& dir, const PanelData& p);

// The reference model's result of the last frame: the check's, else run now (--no-check).
PipelineResult last_frame_model(const HwConfig& hw, const RegisterPlan& plan, const ModelCheck& check);

}  // namespace sm::simapp
