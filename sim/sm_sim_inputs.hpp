// stereo_sim's inputs: the camera frames (a stereo pair, a sequence, a video or a scene),
// streamed from their source at the active size (sm_frame_source.hpp), and the scene's
// ground truth when it has one.
#pragma once

#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "sm_frame_source.hpp"
#include "sm_sim_options.hpp"
#include "sm_types.hpp"

namespace sm::simapp {

struct SimInput {
  std::unique_ptr<FrameSource> source;  // the frames, read one at a time
  size_t first = 0;                     // this run's first frame (a shard: --frame-range)
  size_t nframes = 0;                   // frames this run streams
  size_t total = 0;                     // frames of the whole run (a shard's and the others')
  cv::Mat gt;                           // CV_32F disparity, 0 = unknown (empty when none)
  cv::Mat mask;                         // 8-bit evaluation mask (empty: all known gt)
  std::string name;
  std::string gt_note;  // how the ground truth was resized (empty: at its own size)
  double gt_scale = 1;  // disparity factor applied to the ground truth
};

// Opens the input the options name and counts its frames (FrameSource::note says how
// many run and why); reads no frame yet. Throws on an unreadable or inconsistent input.
SimInput open_inputs(const SimOptions& opt);

// The active size: frames are resized to it as they are read, the ground truth now.
void fit_inputs(const SimOptions& opt, int width, int height, SimInput& in);

}  // namespace sm::simapp
