// stereo_sim's inputs (sm_sim_inputs.hpp).
#include "sm_sim_inputs.hpp"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>

#include "toolio/sm_io.hpp"

namespace sm::simapp {

namespace {

// The scene's ground truth at the active size.
void fit_ground_truth(const tools::Scene& sc, int width, int height, SimInput& in) {
  if (sc.gt.empty()) return;
  if (sc.gt.cols == width && sc.gt.rows == height) {
    in.gt = sc.gt;
    in.mask = sc.nonocc;
    return;
  }
  // Resized scene: ground truth resized by nearest neighbour (no blending across depth
  // edges) and its disparities scaled by the width ratio.
  in.gt_scale = static_cast<double>(width) / sc.gt.cols;
  cv::resize(sc.gt, in.gt, cv::Size(width, height), 0, 0, cv::INTER_NEAREST);
  in.gt *= in.gt_scale;
  if (!sc.nonocc.empty()) cv::resize(sc.nonocc, in.mask, cv::Size(width, height), 0, 0, cv::INTER_NEAREST);
  in.gt_note = fmt::format("ground truth resized from {}x{} (nearest neighbour), disparities x {:.4f}", sc.gt.cols,
                           sc.gt.rows, in.gt_scale);
}

bool is_scene_input(const SimOptions& opt) {
  return opt.left.empty() && opt.right.empty() && opt.seq_dir.empty() && opt.video.empty();
}

}  // namespace

SimInput open_inputs(const SimOptions& opt) {
  SimInput in;
  in.source = open_frame_source(opt);
  in.nframes = in.total = in.source->count();
  in.name = in.source->name();
  return in;
}

void fit_inputs(const SimOptions& opt, int width, int height, SimInput& in) {
  in.source->set_size(width, height);
  if (is_scene_input(opt)) fit_ground_truth(load_sim_scene(opt.scene_dir), width, height, in);
}

}  // namespace sm::simapp
