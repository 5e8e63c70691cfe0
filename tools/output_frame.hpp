// One scene as the output-stage studies see it (sm_output_study, docs/evaluation.md,
// "Sub-pixel, validity and confidence"): the reference pipeline's per-pixel evidence and
// post-processed level, the rectified left image and the ground truth.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "evidence.hpp"
#include "outword.hpp"
#include "sm_types.hpp"

namespace sm::tools {

struct OutputFrame {
  std::string name;
  int levels = 0;
  Evidence ev;
  DispImage post;
  cv::Mat left;                      // CV_8UC1, the pair's left view as the pipeline read it
  cv::Mat gt, mask;                  // CV_32F ground truth (0 unknown) and the optional non-occlusion mask
  cv::Mat margin;                    // CV_32S trellis margin of the dense output's level (sm_dp_margin.hpp), when asked
  cv::Mat margin_fwd;                // CV_32S the same margin from the forward pass alone (dp_forward_excess)
  OutImage dense_raw, dense_stream;  // with the margin: the dense words before and after the smoothing
};

}  // namespace sm::tools
