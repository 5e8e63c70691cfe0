// stereo_sim's inputs: the camera frames (a stereo pair, a sequence, a video or a scene)
// at the active size, and the scene's ground truth when it has one.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "sm_sim_options.hpp"
#include "sm_types.hpp"

namespace sm::simapp {

struct SimInput {
  std::vector<std::pair<Image8, Image8>> frames;  // (left, right) at the active size
  cv::Mat gt;                                     // CV_32F disparity, 0 = unknown (empty when none)
  cv::Mat mask;                                   // 8-bit evaluation mask (empty: all known gt)
  std::string name;
  std::string gt_note;  // how the ground truth was resized (empty: at its own size)
  double gt_scale = 1;  // disparity factor applied to the ground truth
};

// Reads up to opt.frames frames from the input the options name, resized to width x
// height (said on stderr unless quiet). Throws on an unreadable or inconsistent input.
SimInput open_inputs(const SimOptions& opt, int width, int height);

}  // namespace sm::simapp
