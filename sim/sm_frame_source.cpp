// stereo_sim's frame sources (sm_frame_source.hpp).
#include "sm_frame_source.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <utility>
#include <vector>

#include "sm_sim_options.hpp"
#include "toolio/sm_io.hpp"

namespace fs = std::filesystem;

namespace sm::simapp {

Image8 FrameSource::fit(const cv::Mat& grey) {
  cv::Mat g = grey;
  if (g.cols != width_ || g.rows != height_) {
    cv::resize(grey, g, cv::Size(width_, height_), 0, 0, cv::INTER_AREA);
    resized_ = true;
  }
  return tools::to_image8(g);
}

namespace {

// How many of `available` frames run: all, unless --frames limits them.
size_t limit(const SimOptions& opt, size_t available, const std::string& what, std::string& note) {
  if (opt.frames > 0 && static_cast<size_t>(opt.frames) < available) {
    note = fmt::format("{} of the {} frames of {} (--frames {})", opt.frames, available, what, opt.frames);
    return static_cast<size_t>(opt.frames);
  }
  note = opt.frames > 0 && static_cast<size_t>(opt.frames) > available
             ? fmt::format("all {} frames of {} (--frames {} asks for more)", available, what, opt.frames)
             : fmt::format("all {} frames of {}", available, what);
  return available;
}

// A left and a right image of the same size, as read.
std::pair<cv::Mat, cv::Mat> load_pair(const std::string& left, const std::string& right) {
  cv::Mat l = tools::load_grey_mat(left), r = tools::load_grey_mat(right);
  if (l.size() != r.size())
    fail(fmt::format("{}: {}x{} does not match {}: {}x{}", left, l.cols, l.rows, right, r.cols, r.rows));
  return {std::move(l), std::move(r)};
}

// A stereo pair or a scene: one frame streamed `count` times (--frames, default 2).
class RepeatSource : public FrameSource {
 public:
  RepeatSource(cv::Mat l, cv::Mat r, const SimOptions& opt, const std::string& name)
      : l_(std::move(l)), r_(std::move(r)) {
    count_ = available_ = static_cast<size_t>(opt.frames > 0 ? opt.frames : 2);
    name_ = name;
    note_ = fmt::format("one pair streamed {} times ({})", count_,
                        opt.frames > 0 ? fmt::format("--frames {}", opt.frames) : std::string("default, --frames"));
  }
  StereoFrame next() override {
    if (!have_) {
      frame_ = {fit(l_), fit(r_)};
      have_ = true;
    }
    return frame_;
  }
  void skip(size_t) override {}

 private:
  cv::Mat l_, r_;
  StereoFrame frame_;
  bool have_ = false;
};

// A folder of left*/right* images, paired in name order.
class SequenceSource : public FrameSource {
 public:
  SequenceSource(const SimOptions& opt) {
    const std::string& dir = opt.seq_dir;
    if (!fs::is_directory(dir)) fail(fmt::format("{}: not a folder", dir));
    for (auto& e : fs::directory_iterator(dir)) {
      const auto n = e.path().filename().string();
      if (n.rfind("left", 0) == 0) ls_.push_back(e.path().string());
      if (n.rfind("right", 0) == 0) rs_.push_back(e.path().string());
    }
    std::sort(ls_.begin(), ls_.end());
    std::sort(rs_.begin(), rs_.end());
    if (ls_.empty() || ls_.size() != rs_.size())
      fail(fmt::format("{}: {} left* and {} right* images (need equal, non-zero counts)", dir, ls_.size(), rs_.size()));
    available_ = ls_.size();
    count_ = limit(opt, available_, "the sequence", note_);
    name_ = dir;
  }
  StereoFrame next() override {
    if (i_ >= ls_.size()) fail(fmt::format("{}: no frame {}", name_, i_));
    const auto [l, r] = load_pair(ls_[i_], rs_[i_]);
    StereoFrame fr{fit(l), fit(r)};
    ++i_;
    return fr;
  }
  void skip(size_t n) override { i_ += n; }

 private:
  std::vector<std::string> ls_, rs_;
  size_t i_ = 0;
};

// A side-by-side stereo video (left half, right half). Its frames are counted by one
// pass over the file when it is opened (container frame counts are not reliable); a
// video that ends before the frames its header declares (truncated, damaged) is an
// error, not a shorter run.
class VideoSource : public FrameSource {
 public:
  VideoSource(const SimOptions& opt) : path_(opt.video) {
    // FFmpeg would play a single picture as a one-frame video
    if (cv::haveImageReader(path_))
      fail(fmt::format("--video {}: a picture, not a video (a pair is --left/--right)", path_));
    tools::StderrMute quiet;  // FFmpeg's own complaints: the error line is ours
    cv::VideoCapture cap(path_);
    if (!cap.isOpened()) fail(fmt::format("{}: not a video OpenCV can read", path_));
    const double declared = cap.get(cv::CAP_PROP_FRAME_COUNT);
    const size_t want = opt.frames > 0 ? static_cast<size_t>(opt.frames) : ~size_t{0};
    while (available_ <= want && cap.grab()) ++available_;  // one past the limit: "of N" is then a lower bound
    if (available_ == 0) fail(fmt::format("{}: no frames could be read", path_));
    if (declared > 0 && available_ < std::min(want, static_cast<size_t>(declared)))
      fail(fmt::format("{}: only {} of the {} frames it declares could be read (truncated or damaged)", path_,
                       available_, static_cast<size_t>(declared)));
    count_ = limit(opt, available_, "the video", note_);
    if (count_ < available_) note_ = fmt::format("{} frames of the video (--frames {})", count_, opt.frames);
    name_ = path_;
    cap_.open(path_);
  }
  StereoFrame next() override {
    cv::Mat f, g;
    tools::StderrMute quiet;  // FFmpeg's own complaints: the error line is ours
    if (!cap_.read(f)) fail(fmt::format("{}: frame {} could not be read", path_, i_));
    if (f.cols < 2) fail(fmt::format("{}: frame too narrow", path_));
    if (f.channels() == 3)
      cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
    else
      g = f;
    const int hw2 = g.cols / 2;
    ++i_;
    return {fit(g(cv::Rect(0, 0, hw2, g.rows))), fit(g(cv::Rect(hw2, 0, hw2, g.rows)))};
  }

 private:
  std::string path_;
  cv::VideoCapture cap_;
  size_t i_ = 0;
};

}  // namespace

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

std::unique_ptr<FrameSource> open_frame_source(const SimOptions& opt) {
  if (!opt.left.empty() || !opt.right.empty()) {
    if (opt.left.empty() || opt.right.empty()) fail("--left and --right go together");
    auto [l, r] = load_pair(opt.left, opt.right);
    return std::make_unique<RepeatSource>(std::move(l), std::move(r), opt, opt.left);
  }
  if (!opt.seq_dir.empty()) return std::make_unique<SequenceSource>(opt);
  if (!opt.video.empty()) return std::make_unique<VideoSource>(opt);
  const tools::Scene sc = load_sim_scene(opt.scene_dir);
  return std::make_unique<RepeatSource>(sc.left, sc.right, opt, opt.scene_dir);
}

const StereoFrame& FrameWindow::at(size_t f) {
  if (f < base_) fail(fmt::format("frame {} was already released", f));
  while (base_ + frames_.size() <= f) frames_.push_back(src_.next());
  return frames_[f - base_];
}

void FrameWindow::release(size_t f) {
  while (base_ < f && !frames_.empty()) {
    frames_.pop_front();
    ++base_;
  }
}

}  // namespace sm::simapp
