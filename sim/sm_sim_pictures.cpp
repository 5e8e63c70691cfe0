// stereo_sim's pictures (sm_sim_pictures.hpp).
#include "sm_sim_pictures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "toolio/sm_depth.hpp"
#include "toolio/sm_io.hpp"

namespace sm::simapp {

namespace {

using tools::labelled;

// Tiles are drawn at least this many rows tall (a small configuration's 48 rows are
// magnified by whole pixels), so that labels, ticks and legends stay readable.
constexpr int kMinTileRows = 240;

// `m` magnified k times, pixels kept whole (nearest neighbour).
cv::Mat zoom(const cv::Mat& m, int k) {
  if (k == 1 || m.empty()) return m;
  cv::Mat z;
  cv::resize(m, z, cv::Size(), k, k, cv::INTER_NEAREST);
  return z;
}

void stage_image(tools::OutputSet& outs, const std::string& path, const cv::Mat& img,
                 const std::vector<int>& params = {}) {
  outs.write(
      path, [&](const std::string& temp) { tools::write_image_atomic(temp, img, params); }, true);
}

cv::Mat bgr(const Image8& im, int k) {
  cv::Mat c;
  cv::cvtColor(tools::to_mat(im), c, cv::COLOR_GRAY2BGR);
  return zoom(c, k);
}

// The boxes of `objects` at magnification k.
std::vector<Object> zoom_objects(std::vector<Object> objects, int k) {
  for (auto& o : objects) {
    o.x0 = static_cast<uint16_t>(o.x0 * k);
    o.y0 = static_cast<uint16_t>(o.y0 * k);
    o.x1 = static_cast<uint16_t>(o.x1 * k + k - 1);
    o.y1 = static_cast<uint16_t>(o.y1 * k + k - 1);
  }
  return objects;
}

// The ground truth as a disparity picture's input: unknown (0) is invalid.
cv::Mat gt_disparity(const cv::Mat& gt) {
  cv::Mat g = gt.clone();
  g.setTo(-1.0f, gt <= 0);
  return g;
}

// The rows one under the other, each padded on the right with black to the widest.
cv::Mat stack_rows(const std::vector<cv::Mat>& rows) {
  int w = 0;
  for (const auto& r : rows) w = std::max(w, r.cols);
  std::vector<cv::Mat> padded;
  for (const auto& r : rows) {
    cv::Mat p;
    cv::copyMakeBorder(r, p, 0, 0, 0, w - r.cols, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    padded.push_back(p);
  }
  cv::Mat out;
  cv::vconcat(padded, out);
  return out;
}

// The objects tile: the RTL's last packet (else the model's list) on the colour disparity
// `disp_z` (magnified k times).
cv::Mat objects_tile(const PanelData& p, const PipelineResult& m, const cv::Mat& disp_z, int k) {
  const bool rtl = p.packets && !p.packets->empty();
  const std::vector<Object>& boxes = rtl ? p.packets->back().objects : m.objects.objects;
  const bool too_many = rtl ? p.packets->back().too_many : m.objects.too_many_objects;
  const bool full = rtl ? p.packets->back().table_full : m.objects.table_full;
  return labelled(tools::draw_objects(tools::colourise(disp_z, p.range), zoom_objects(boxes, k), too_many, full),
                  fmt::format("objects ({})", boxes.size()));
}

// The bird's-eye view of the last frame's point cloud (grey values of the rectified left),
// `size` pixels.
cv::Mat cloud_tile(const PanelData& p, const Image8& rect_left, cv::Size size) {
  const cv::Mat z = tools::disparity_to_depth(*p.disp, *p.cam);
  const double cut = p.cloud_max_depth > 0 ? p.cloud_max_depth : INFINITY;
  const auto pts = tools::depth_to_cloud(z, tools::to_mat(rect_left), *p.cam, cut);
  return labelled(tools::cloud_view(pts, size, p.cloud_max_depth),
                  fmt::format("point cloud, bird's-eye ({} points)", pts.size()));
}

// The error map and the ground truth, magnified k times.
cv::Mat ground_truth_row(const PanelData& p, const cv::Mat& disp_z, int k) {
  const cv::Mat gt = zoom(p.in->gt, k), mask = zoom(p.in->mask, k);
  return tools::side_by_side(
      {labelled(tools::error_map_picture(disp_z, gt, mask), fmt::format("error map (bad-1.0 {:.1f} %)", p.bad1)),
       labelled(tools::disparity_picture(gt_disparity(gt), p.range, p.cam), "ground truth")});
}

}  // namespace

tools::ColourRange picture_range(const SimInput& in, const cv::Mat& disp) {
  return tools::data_range(in.gt.empty() ? disp : gt_disparity(in.gt));
}

void write_disparity_pictures(tools::OutputSet& outs, const std::string& dir, const cv::Mat& disp, const HwConfig& hw,
                              tools::ColourRange r, const RectCamera* cam) {
  stage_image(outs, dir + "/disparity.png", tools::disp_to_grey(disp, hw.disp));
  stage_image(outs, dir + "/disparity_color.png", tools::disparity_picture(disp, r, cam));
}

PipelineResult last_frame_model(const HwConfig& hw, const RegisterPlan& plan, const ModelCheck& check) {
  const auto& frame = check.last_input;
  return !check.last_model ? run_pipeline(frame.first, frame.second, hw, plan.regs.back(), false) : *check.last_model;
}

void write_panel(tools::OutputSet& outs, const std::string& dir, const PanelData& p) {
  const SimInput& in = *p.in;
  const StereoFrame& frame = *p.frame;
  const PipelineResult& m = *p.model;
  const int k = std::max(1, (kMinTileRows + p.disp->rows - 1) / p.disp->rows);
  const cv::Mat disp_z = zoom(*p.disp, k);
  std::vector<cv::Mat> rows;
  rows.push_back(tools::side_by_side({labelled(bgr(frame.first, k), "left"), labelled(bgr(frame.second, k), "right")}));
  rows.push_back(
      tools::side_by_side({labelled(bgr(m.rl, k), "rectified left"), labelled(bgr(m.rr, k), "rectified right")}));
  rows.push_back(tools::side_by_side(
      {labelled(tools::disparity_picture(disp_z, p.range, p.cam), "disparity"), objects_tile(p, m, disp_z, k)}));
  if (!in.gt.empty()) rows.push_back(ground_truth_row(p, disp_z, k));
  if (p.cam) rows.push_back(cloud_tile(p, m.rl, {2 * disp_z.cols, disp_z.rows}));
  // the strongest PNG compression: magnified tiles are runs of equal pixels (the small
  // configuration's panel: 69 KB instead of 298 KB at OpenCV's default level)
  stage_image(outs, dir + "/panel.png", stack_rows(rows), {cv::IMWRITE_PNG_COMPRESSION, 9});
}

}  // namespace sm::simapp
