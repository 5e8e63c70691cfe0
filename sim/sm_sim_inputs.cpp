// stereo_sim's inputs (sm_sim_inputs.hpp).
#include "sm_sim_inputs.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
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

// FFmpeg prints its own complaints ("[png @ 0x...] ...") on stderr, past OpenCV's log
// level; the one error line is ours, so stderr is parked on /dev/null while it decodes.
class QuietStderr {
 public:
  QuietStderr() {
    std::fflush(stderr);
    saved_ = dup(2);
    const int nul = open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && nul >= 0) dup2(nul, 2);
    if (nul >= 0) close(nul);
  }
  ~QuietStderr() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      dup2(saved_, 2);
      close(saved_);
    }
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_ = -1;
};

// A side-by-side stereo video: left half, right half. A video that ends before the
// frames its header declares (truncated, damaged) is an error, not a shorter run.
void read_video(const SimOptions& opt, Sizer& size, SimInput& in) {
  // FFmpeg would play a single picture as a one-frame video
  if (cv::haveImageReader(opt.video))
    fail(fmt::format("--video {}: a picture, not a video (a pair is --left/--right)", opt.video));
  QuietStderr quiet;
  cv::VideoCapture cap(opt.video);
  if (!cap.isOpened()) fail(fmt::format("{}: not a video OpenCV can read", opt.video));
  const double declared = cap.get(cv::CAP_PROP_FRAME_COUNT);
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
  const size_t want = std::min(static_cast<size_t>(opt.frames), declared > 0 ? static_cast<size_t>(declared) : 0);
  if (in.frames.size() < want)
    fail(fmt::format("{}: only {} of the {} frames it declares could be read (truncated or damaged)", opt.video,
                     in.frames.size(), static_cast<size_t>(declared)));
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

// A scene's left.png and right.png, and its ground truth when it has gt.png (which needs
// scale.txt, the factor of its disparities). Without gt.png the run is not scored.
tools::Scene load_sim_scene(const std::string& dir) {
  const fs::path d(dir);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(fmt::format("--scene {}: no such folder", dir));
  if (fs::exists(d / "gt.png", ec)) {
    if (!fs::exists(d / "scale.txt", ec))
      fail(fmt::format("{}: no such file (gt.png's disparities need its scale)", (d / "scale.txt").string()));
    return tools::load_scene(dir);
  }
  tools::Scene sc;
  sc.dir = dir;
  sc.left = tools::load_grey_mat((d / "left.png").string());
  sc.right = tools::load_grey_mat((d / "right.png").string());
  if (sc.left.size() != sc.right.size())
    fail(fmt::format("{}: left {}x{} and right {}x{} differ in size", dir, sc.left.cols, sc.left.rows, sc.right.cols,
                     sc.right.rows));
  return sc;
}

void read_scene(const SimOptions& opt, Sizer& size, SimInput& in) {
  const tools::Scene sc = load_sim_scene(opt.scene_dir);
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
  // a warning, not progress: shown with -q too
  if (size.resized) fmt::print(stderr, "note: input resized to the active size {}x{}\n", width, height);
  return in;
}

}  // namespace sm::simapp
