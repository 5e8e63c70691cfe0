// The depth and point-cloud options of a tool (--depth-file, --cloud, --cloud-max-depth,
// --cloud-view; docs/calibration.md, "Depth and point-cloud outputs"), shared by
// stereo_model and the harness: add() to the command line, check() before any work,
// write() into the tool's OutputSet with the others.
#pragma once

#include <optional>
#include <opencv2/core.hpp>
#include <string>

#include "calib_file.hpp"
#include "sm_outputs.hpp"

namespace CLI {
class App;
}

namespace sm::tools {

struct DepthOptions {
  std::string depth_file;      // .pfm metres or .png millimetres (write_depth_file)
  std::string cloud;           // .ply (write_ply)
  std::string cloud_view;      // .png bird's-eye view (cloud_view)
  double cloud_max_depth = 0;  // metres; 0: no cut

  bool any() const { return !depth_file.empty() || !cloud.empty() || !cloud_view.empty(); }
  // Adds the four options to `app`.
  void add(CLI::App& app);
  // Everything that can be checked before the work: the file names' extensions, the cut,
  // and that a camera is there when an output is asked for (`camera` from the calibration
  // file `calib`, "" when none was given). Throws ToolError with one line.
  void check(const std::optional<RectCamera>& camera, const std::string& calib) const;
  // Stages the asked-for outputs in `outs`: depth from disp_f (CV_32F, negative / non-finite
  // = invalid, sub-pixel welcome), the cloud's grey values from `grey` (CV_8UC1, the
  // rectified left image). Nothing when any() is false.
  void write(OutputSet& outs, const cv::Mat& disp_f, const cv::Mat& grey, const RectCamera& cam) const;
};

}  // namespace sm::tools
