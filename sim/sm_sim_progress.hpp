// stereo_sim's progress on stderr: after each output row of a run longer than a few
// seconds, the frame and row, the rows per second and the time left; one line rewritten
// in place on a terminal, a plain line every few seconds otherwise (a log). Off with -q.
#pragma once

#include <chrono>
#include <cstddef>

namespace sm::simapp {

class SimProgress {
 public:
  // `frames` x `height` output rows in all; `quiet`: print nothing.
  SimProgress(size_t frames, int height, bool quiet);
  // Output row `row` (0-based) of frame `frame` (0-based) is complete: cheap unless a line is due.
  void row(size_t frame, int row);
  // `done` of `total` frames are out (the frame's line; the last one ends the progress line).
  void frame(size_t done, size_t total);

 private:
  using Clock = std::chrono::steady_clock;
  double seconds() const;
  size_t frames_;
  int height_;
  bool quiet_, tty_;
  Clock::time_point t0_;
  double next_ = 0;  // seconds: the next progress line is due
  // The rate counts from the first output row: the time before it (the pipeline's fill,
  // the set-up) made the first estimates of a run many times too long.
  double first_s_ = -1, first_done_ = 0;
};

}  // namespace sm::simapp
