// stereo_sim's calibrated camera and its metric outputs (issue 42): the calibration whose
// camera turns disparity into metres (--calib, else a --scene folder's calib.json), and
// the depth file, point cloud and cloud view of the last frame (--depth-file, --cloud,
// --cloud-max-depth, --cloud-view; toolio/sm_depth_options.hpp).
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "calib_file.hpp"
#include "sm_sim_options.hpp"
#include "sm_types.hpp"
#include "toolio/sm_outputs.hpp"

namespace sm::simapp {

struct SimCamera {
  std::optional<RectCamera> camera;  // the calibration's camera (none: no metric outputs)
  std::string calib;                 // the calibration file used ("" none)
  bool from_scene = false;           // it is the --scene folder's calib.json
  std::string note;                  // for the report: which calibration, or why none
};

// The options stage's part for the camera: a --scene run with no --calib (and no 'calib',
// 'width' or 'height' in --regs) takes the scene folder's calib.json when it is for the
// active size and this IP's RECT_RADIUS (opt.calib is set to it); the camera is read from opt.calib; the depth
// options are checked against it. Throws one line (the calibration's file named).
SimCamera resolve_camera(SimOptions& opt, const HwConfig& hw);

// report.json's "calibration": the file used (null: none), whether it is the scene's, its
// camera (null: none) and the note (which calibration, or why none).
void add_calibration_report(const SimCamera& cam, nlohmann::json& report);

// The depth outputs of the last frame: `disp` float disparity (sub-pixel welcome,
// negative = invalid), `rect_left` the rectified left image (the cloud's grey values).
// All or nothing. Nothing when none was asked for.
void write_depth_outputs(tools::OutputSet& outs, const SimOptions& opt, const SimCamera& cam, const cv::Mat& disp,
                         const Image8& rect_left);

}  // namespace sm::simapp
