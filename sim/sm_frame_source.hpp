// stereo_sim's frame sources: the camera frames of a stereo pair or scene (one frame
// repeated), a sequence folder (left*/right* pairs sorted by name) or a side-by-side
// video, read one at a time when the camera needs them, so that a run holds a few frames
// whatever its length (issue 40). FrameWindow keeps the frames between the camera and the
// model check (the frames in flight in the IP).
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "sm_sim.hpp"
#include "sm_types.hpp"
#include "toolio/sm_io.hpp"

namespace sm::simapp {

struct SimOptions;

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  size_t count() const { return count_; }            // frames the run streams (after --frames)
  size_t available() const { return available_; }    // frames the input has (a still pair: unbounded, = count)
  const std::string& note() const { return note_; }  // how many frames run and why
  const std::string& name() const { return name_; }
  // The active size frames are resized to (INTER_AREA); `resized()`: one was.
  void set_size(int width, int height) {
    width_ = width;
    height_ = height;
  }
  bool resized() const { return resized_; }
  // The next frame in order; throws on an unreadable frame.
  virtual StereoFrame next() = 0;
  // Skips n frames (a shard starting at a later frame).
  virtual void skip(size_t n) {
    for (size_t i = 0; i < n; ++i) next();
  }

 protected:
  Image8 fit(const cv::Mat& grey);
  size_t count_ = 0, available_ = 0;
  std::string note_, name_;
  int width_ = 0, height_ = 0;
  bool resized_ = false;
};

// A scene's left.png and right.png, and its ground truth when it has gt.png (which needs
// scale.txt, the factor of its disparities). Without gt.png the run is not scored.
tools::Scene load_sim_scene(const std::string& dir);

// Opens the input the options name (--left/--right, --sequence, --video, else --scene)
// and decides how many frames run: a sequence or video all of its frames unless
// --frames limits it, a pair or scene --frames copies (2 unless given). Reads no frame
// yet. Throws on an unreadable or inconsistent input.
std::unique_ptr<FrameSource> open_frame_source(const SimOptions& opt);

// The frames from `first` on, read when first asked for and dropped by release().
class FrameWindow {
 public:
  explicit FrameWindow(FrameSource& src) : src_(src) {}
  // Frame f (f >= the last release); frames are read in order up to it.
  const StereoFrame& at(size_t f);
  // Frames before f are no longer needed.
  void release(size_t f);
  size_t held() const { return frames_.size(); }

 private:
  FrameSource& src_;
  std::deque<StereoFrame> frames_;
  size_t base_ = 0;  // index of frames_.front()
};

}  // namespace sm::simapp
