// The host's speckle check (docs/evaluation.md, "Speckles"): what a host that holds a whole
// frame of the IP's stream can add to the checked mode. A connected region of valid pixels
// whose 4-neighbours differ by at most DIFF/16 px, of at most SIZE pixels, becomes invalid
// (OpenCV's filterSpeckles on the Q.4 values). The IP does not do this itself: it decides a
// pixel rows before the region around it has closed, and holding the rows costs more area
// than issue 39 allows. Measured on the 14 scenes with LR_EN, AGREE_EN and SMOOTH_EN 0 in
// the IP (sm_evaluate's `model_host`). stereo_model's --speckle: add() to the command line,
// apply() to the disparity before any output is made from it.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace CLI {
class App;
}

namespace sm::tools {

// Defaults chosen on all 14 scenes at once (sm_output_study --study speckle).
constexpr int kHostSpeckleSize = 1000;
constexpr int kHostSpeckleDiff = 8;

// Pixels of disp_f (CV_32F; negative or non-finite = invalid, sub-pixel welcome) in
// speckles of at most max_size pixels whose 4-neighbours differ by at most max_diff/16 px
// are set to -1 (invalid). Returns how many were cleared. max_size 0: nothing changes.
long host_speckle(cv::Mat& disp_f, int max_size, int max_diff);

struct HostSpeckleOptions {
  int max_size = 0;                 // --speckle SIZE; 0: off
  int max_diff = kHostSpeckleDiff;  // --speckle SIZE,DIFF

  bool on() const { return max_size > 0; }
  // Adds --speckle SIZE[,DIFF] to `app` (SIZE 0..2^24, 0 = off; DIFF 0..255; checked by the
  // parser, one line naming the value: "--speckle: 300: outside 0..255").
  void add(CLI::App& app);
  // Applies the check to disp_f when on(); returns the pixels cleared.
  long apply(cv::Mat& disp_f) const { return on() ? host_speckle(disp_f, max_size, max_diff) : 0; }
  // "speckles of at most SIZE px within DIFF/16 px" for reports.
  std::string describe() const;
};

}  // namespace sm::tools
