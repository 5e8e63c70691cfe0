// stereo_sim's lossless disparity files (--disp-file, --disp-each-frame).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sm_sim.hpp"
#include "sm_sim_options.hpp"
#include "toolio/sm_outputs.hpp"
#include "toolio/sm_signal_cleanup.hpp"

namespace sm::simapp {

// opt.disp_file of the last frame's `disp` (float disparity), staged in `outs` (the
// per-frame files of --disp-each-frame are FrameFiles', written during the run).
void write_disparity_files(tools::OutputSet& outs, const SimOptions& opt, const cv::Mat& disp);

// <stem>_NNN<ext> beside `disp_file`: frame NNN's disparity file.
std::string frame_disparity_path(const std::string& disp_file, size_t f);

// --disp-each-frame: every frame's disparity file, written as the frame leaves the RTL;
// removed again unless keep() is called (a failed run leaves none behind; Ctrl-C or
// kill neither, while this object lives: each file is registered with RemoveOnSignal).
class FrameFiles {
 public:
  explicit FrameFiles(std::string disp_file) : disp_file_(std::move(disp_file)) {}
  FrameFiles(const FrameFiles&) = delete;
  FrameFiles& operator=(const FrameFiles&) = delete;
  ~FrameFiles();
  void write(size_t f, const OutImage& disp);
  void keep() { kept_ = true; }

 private:
  std::string disp_file_;
  std::vector<std::string> written_;
  std::vector<tools::RemoveOnSignal> on_signal_;
  bool kept_ = false;
};

}  // namespace sm::simapp
