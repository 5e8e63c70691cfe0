// stereo_sim's progress (sm_sim_progress.hpp).
#include "sm_sim_progress.hpp"

#include "sm_sim_interrupt.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace sm::simapp {

namespace {
// No progress line before this many seconds: a short run stays quiet.
constexpr double kFirstLine = 3.0;
// Seconds between lines: rewritten in place on a terminal, appended in a log.
constexpr double kTtyEvery = 0.5, kLogEvery = 10.0;
}  // namespace

SimProgress::SimProgress(size_t frames, int height, bool quiet)
    : frames_(frames), height_(height), quiet_(quiet), tty_(isatty(fileno(stderr)) != 0), t0_(Clock::now()) {
  next_ = kFirstLine;
}

double SimProgress::seconds() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }

void SimProgress::row(size_t frame, int row) {
  if (quiet_) return;
  const double s = seconds();
  const double done = static_cast<double>(frame) * height_ + row + 1;
  if (first_s_ < 0) first_s_ = s, first_done_ = done;
  if (s < next_) return;
  next_ = s + (tty_ ? kTtyEvery : kLogEvery);
  const double total = static_cast<double>(frames_) * height_;
  const double rate = s > first_s_ ? (done - first_done_) / (s - first_s_) : 0;
  const std::string speed = rate > 0 ? fmt::format("{:.1f} rows/s, {:.0f} s left", rate, (total - done) / rate)
                                     : std::string("rows/s and time left not known yet");
  const std::string line = fmt::format("frame {}/{} row {}/{}: {}", frame + 1, frames_, row + 1, height_, speed);
  if (tty_) {
    fmt::print(stderr, "\r{:<72}", line);
    set_progress_line_open(true);
  } else {
    fmt::print(stderr, "stereo_sim: {}\n", line);
  }
}

void SimProgress::frame(size_t done, size_t total) {
  if (quiet_) return;
  const double s = seconds();
  const std::string line = fmt::format("simulated frame {}/{} ({:.1f} s)", done, total, s);
  if (tty_) {
    // once the row lines run (they name the frame too), only the last frame's line
    if (done < total && s >= kFirstLine) return;
    fmt::print(stderr, "\r{:<72}", line);
    set_progress_line_open(done != total);
    if (done == total) fmt::print(stderr, "\n");
  } else if (done == total || s >= next_) {  // a log: the last frame, else as often as the row lines
    next_ = s + kLogEvery;
    fmt::print(stderr, "{}\n", line);
  }
}

}  // namespace sm::simapp
