// Accuracy metrics of sub-pixel and checked outputs (docs/evaluation.md, "Sub-pixel,
// validity and confidence"): bad-0.5/1.0/2.0, mean absolute error and density, and the
// sparsification curve of a confidence map against its oracle.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "outword.hpp"

namespace sm::tools {

// Evaluated pixels: known ground truth (gt > 0) and, where a mask is given, set in it.
bool evaluated(const cv::Mat& gt, const cv::Mat& mask, int y, int x);

// Over the evaluated pixels; est_f CV_32F, < 0 invalid.
struct DispMetrics {
  long evaluated = 0, valid = 0;
  long bad05 = 0, bad1 = 0, bad2 = 0;  // dense: invalid pixels count as bad
  long bad1_valid = 0;                 // bad-1.0 among the valid pixels
  double abs_err = 0;                  // summed over the valid pixels
  double pct(long n) const { return evaluated ? 100.0 * n / evaluated : 0.0; }
  double density() const { return pct(valid); }
  double bad1_of_valid() const { return valid ? 100.0 * bad1_valid / valid : 0.0; }
  double mae() const { return valid ? abs_err / valid : 0.0; }
};
DispMetrics disp_metrics(const cv::Mat& est_f, const cv::Mat& gt, const cv::Mat& mask);

// Sparsification of bad-1.0 over the evaluated pixels: pixels dropped in increasing order
// of confidence (CV_8U, same size; invalid estimates count as bad and keep their
// confidence), ties dropped as a group at their mean error (the expectation over tie
// orders). curve[k] = bad-1.0 % of the kept pixels at kept share (k + 1) / steps; auc = the
// mean of curve (right Riemann sum, % x share). The oracle drops the bad pixels first.
struct Sparsification {
  std::vector<double> curve, oracle;
  double auc = 0, oracle_auc = 0;
};
Sparsification sparsification(const cv::Mat& est_f, const cv::Mat& conf, const cv::Mat& gt, const cv::Mat& mask,
                              int steps = 100);

// The output words' Q.4 disparity as float pixels and their confidence. Invalid pixels
// are negative: kNoMatchDisp where the occlusion or border rule cleared them (no match
// exists: the pictures paint them apart), else -1.
constexpr float kNoMatchDisp = -2.0f;
cv::Mat out_to_float(const OutImage& o);
cv::Mat out_to_conf(const OutImage& o);

// Invalid words of a frame and, per validity rule, how many of them it cleared (a pixel
// may fail several): the rules in the order of their bits in the word (docs/algorithm.md
// 9.4), bits 29:24, then the speckle stage's bit 30 (9.8).
struct FailCounts {
  static constexpr int kN = 7;
  static constexpr const char* kRules[kN] = {"occlusion", "border",     "uniqueness", "agreement",
                                             "texture",   "left_right", "speckle"};
  long pixels = 0, invalid = 0;
  long by_rule[kN] = {};
};
FailCounts fail_counts(const OutImage& o);
// "N of M pixels invalid: occlusion a, border b, ..." (the rules that cleared any).
std::string fail_counts_line(const FailCounts& c);

}  // namespace sm::tools
