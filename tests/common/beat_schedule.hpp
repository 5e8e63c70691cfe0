// The row-step beat sequence of the core's internal streams (docs/algorithm.md,
// "Streaming protocol"): frames of W-beat rows followed by virtual flush rows. Block
// tests drive their stage with it and map output beats back to pixels.
#pragma once

#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "sm_defs.hpp"

namespace sm::test {

// The sideband's flags, as rtl/defs.json lays them out (sm_defs.hpp).
enum SideBit : uint8_t { kReal = defs::kSideReal, kSof = defs::kSideSof, kSol = defs::kSideSol };

struct BeatInfo {
  uint8_t side = 0;  // the 5-bit sideband
  int frame = -1;    // index of the frame, -1 for a virtual row
  int x = 0;
  int y = 0;
};

// frames[i] rows of width w, back to back, then flush_rows virtual rows.
inline std::vector<BeatInfo> make_schedule(int w, const std::vector<int>& heights, int flush_rows,
                                           int gap_rows_between_frames = 0) {
  std::vector<BeatInfo> s;
  int ftag = 0;
  auto push_row = [&](int frame, int y, bool real) {
    for (int x = 0; x < w; ++x) {
      BeatInfo b;
      b.frame = real ? frame : -1;
      b.x = x;
      b.y = y;
      b.side = static_cast<uint8_t>((ftag & 3) << defs::kSideTagLsb);
      if (real) b.side |= kReal;
      if (real && x == 0 && y == 0) b.side |= kSof;
      if (x == 0) b.side |= kSol;
      s.push_back(b);
    }
  };
  for (size_t f = 0; f < heights.size(); ++f) {
    ftag = static_cast<int>(f) & 3;
    for (int y = 0; y < heights[f]; ++y) push_row(static_cast<int>(f), y, true);
    if (f + 1 < heights.size())
      for (int r = 0; r < gap_rows_between_frames; ++r) push_row(-1, 0, false);
  }
  for (int r = 0; r < flush_rows; ++r) push_row(-1, 0, false);
  return s;
}

// Tracks the real output beats of a stage: they must come in raster order, frame
// after frame, with sof/sol where they belong. Returns the (frame, x, y) of a beat.
class OutputOrder {
 public:
  OutputOrder(int w, std::vector<int> heights) : w_(w), heights_(std::move(heights)) {}
  // Throws std::runtime_error on a beat out of order or with a wrong flag.
  BeatInfo next(uint8_t side) {
    if (!(side & kReal)) throw std::runtime_error("next() called on a virtual beat");
    if (frame_ >= static_cast<int>(heights_.size()))
      throw std::runtime_error("more real output beats than pixels sent");
    BeatInfo b;
    b.frame = frame_;
    b.x = x_;
    b.y = y_;
    b.side = side;
    const bool want_sof = x_ == 0 && y_ == 0;
    const bool want_sol = x_ == 0;
    if (((side & kSof) != 0) != want_sof || ((side & kSol) != 0) != want_sol || ((side >> 3) & 3) != (frame_ & 3))
      throw std::runtime_error("output sideband wrong at frame " + std::to_string(frame_) + " x " + std::to_string(x_) +
                               " y " + std::to_string(y_) + " side " + std::to_string(side));
    if (++x_ == w_) {
      x_ = 0;
      if (++y_ == heights_[frame_]) {
        y_ = 0;
        ++frame_;
      }
    }
    return b;
  }
  bool done() const { return frame_ == static_cast<int>(heights_.size()); }

 private:
  int w_;
  std::vector<int> heights_;
  int frame_ = 0, x_ = 0, y_ = 0;
};

// Random clock-enable pattern: ce is low with probability idle_percent / 100. With
// min_gap = F > 1 (a folded block, F = DISP / PU clocks per beat) ce is also low on the
// F - 1 clocks after every high one, as sm_top's pacing guarantees; a bench of a folded
// block then holds the next beat's input from the clock after a ce until its own ce.
class CeGen {
 public:
  CeGen(uint32_t seed, int idle_percent, int min_gap = 1) : rng_(seed), idle_(idle_percent), gap_(min_gap) {}
  bool next() {
    if (wait_ > 0) {
      --wait_;
      return false;
    }
    const bool ce = static_cast<int>(rng_() % 100) >= idle_;
    if (ce) wait_ = gap_ - 1;
    return ce;
  }
  std::mt19937& rng() { return rng_; }

 private:
  std::mt19937 rng_;
  int idle_;
  int gap_;
  int wait_ = 0;
};

}  // namespace sm::test
