// stereo_sim's inputs (sm_sim_inputs.hpp).
#include "sm_sim_inputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "toolio/sm_io.hpp"

namespace fs = std::filesystem;

namespace sm::simapp {

namespace {

// Frames are resized to the active size; `resized` records that one was.
struct Sizer {
  int width, height;
  bool resized = false;
  Image8 operator()(const cv::Mat& grey) {
    cv::Mat g = grey;
    if (g.cols != width || g.rows != height) {
      cv::resize(grey, g, cv::Size(width, height), 0, 0, cv::INTER_AREA);
      resized = true;
    }
    return tools::to_image8(g);
  }
};

void read_pair(const SimOptions& opt, Sizer& size, SimInput& in) {
  if (opt.left.empty() || opt.right.empty()) fail("--left and --right go together");
  cv::Mat l = tools::load_grey_mat(opt.left), r = tools::load_grey_mat(opt.right);
  if (l.size() != r.size())
    fail(fmt::format("{}: {}x{} does not match {}: {}x{}", opt.left, l.cols, l.rows, opt.right, r.cols, r.rows));
  for (int i = 0; i < opt.frames; ++i) in.frames.emplace_back(size(l), size(r));
  in.name = opt.left;
}

void read_sequence(const SimOptions& opt, Sizer& size, SimInput& in) {
  const std::string& dir = opt.seq_dir;
  std::vector<fs::path> ls, rs;
  if (!fs::is_directory(dir)) fail(fmt::format("{}: not a folder", dir));
  for (auto& e : fs::directory_iterator(dir)) {
    const auto n = e.path().filename().string();
    if (n.rfind("left", 0) == 0) ls.push_back(e.path());
    if (n.rfind("right", 0) == 0) rs.push_back(e.path());
  }
  std::sort(ls.begin(), ls.end());
  std::sort(rs.begin(), rs.end());
  if (ls.empty() || ls.size() != rs.size())
    fail(fmt::format("{}: {} left* and {} right* images (need equal, non-zero counts)", dir, ls.size(), rs.size()));
  for (size_t i = 0; i < ls.size() && static_cast<int>(i) < opt.frames; ++i) {
    Image8 l = size(tools::load_grey_mat(ls[i].string()));
    Image8 r = size(tools::load_grey_mat(rs[i].string()));
    in.frames.emplace_back(std::move(l), std::move(r));
  }
  in.name = dir;
}

// A side-by-side stereo video: left half, right half.
void read_video(const SimOptions& opt, Sizer& size, SimInput& in) {
  cv::VideoCapture cap(opt.video);
  if (!cap.isOpened()) fail(fmt::format("{}: cannot open video", opt.video));
  cv::Mat f, g;
  while (static_cast<int>(in.frames.size()) < opt.frames && cap.read(f)) {
    if (f.cols < 2) fail(fmt::format("{}: frame too narrow", opt.video));
    if (f.channels() == 3)
      cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
    else
      g = f;
    const int hw2 = g.cols / 2;
    Image8 l = size(g(cv::Rect(0, 0, hw2, g.rows)));
    Image8 r = size(g(cv::Rect(hw2, 0, hw2, g.rows)));
    in.frames.emplace_back(std::move(l), std::move(r));
  }
  if (in.frames.empty()) fail(fmt::format("{}: no frames could be read", opt.video));
  in.name = opt.video;
}

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

void read_scene(const SimOptions& opt, Sizer& size, SimInput& in) {
  const tools::Scene sc = tools::load_scene(opt.scene_dir);
  const Image8 l = size(sc.left);
  const Image8 r = size(sc.right);
  for (int i = 0; i < opt.frames; ++i) in.frames.emplace_back(l, r);
  fit_ground_truth(sc, size.width, size.height, in);
  in.name = opt.scene_dir;
}

}  // namespace

SimInput open_inputs(const SimOptions& opt, int width, int height) {
  SimInput in;
  Sizer size{width, height};
  if (!opt.left.empty() || !opt.right.empty())
    read_pair(opt, size, in);
  else if (!opt.seq_dir.empty())
    read_sequence(opt, size, in);
  else if (!opt.video.empty())
    read_video(opt, size, in);
  else
    read_scene(opt, size, in);
  if (size.resized && !opt.quiet) fmt::print(stderr, "note: input resized to the active size {}x{}\n", width, height);
  return in;
}

}  // namespace sm::simapp
