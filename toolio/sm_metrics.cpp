#include "toolio/sm_metrics.hpp"

#include <array>
#include <cmath>

#include <fmt/format.h>

#include "speckle.hpp"
#include "validity.hpp"

namespace sm::tools {

bool evaluated(const cv::Mat& gt, const cv::Mat& mask, int y, int x) {
  return gt.at<float>(y, x) > 0 && (mask.empty() || mask.at<uint8_t>(y, x) != 0);
}

DispMetrics disp_metrics(const cv::Mat& est_f, const cv::Mat& gt, const cv::Mat& mask) {
  CV_Assert(est_f.type() == CV_32F && gt.type() == CV_32F && est_f.size() == gt.size());
  CV_Assert(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == gt.size()));
  DispMetrics m;
  for (int y = 0; y < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x) {
      if (!evaluated(gt, mask, y, x)) continue;
      ++m.evaluated;
      const float e = est_f.at<float>(y, x);
      if (e < 0) {
        ++m.bad05, ++m.bad1, ++m.bad2;
        continue;
      }
      ++m.valid;
      const double err = std::fabs(static_cast<double>(e) - gt.at<float>(y, x));
      m.abs_err += err;
      m.bad05 += err > 0.5;
      m.bad1 += err > 1.0;
      m.bad2 += err > 2.0;
      m.bad1_valid += err > 1.0;
    }
  return m;
}

Sparsification sparsification(const cv::Mat& est_f, const cv::Mat& conf, const cv::Mat& gt, const cv::Mat& mask,
                              int steps) {
  CV_Assert(est_f.type() == CV_32F && conf.type() == CV_8UC1 && conf.size() == gt.size() && steps >= 1);
  std::array<double, 256> n{}, bad{};
  double total = 0, total_bad = 0;
  for (int y = 0; y < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x) {
      if (!evaluated(gt, mask, y, x)) continue;
      const float e = est_f.at<float>(y, x);
      const bool b = e < 0 || std::fabs(e - gt.at<float>(y, x)) > 1.0f;
      n[conf.at<uint8_t>(y, x)] += 1;
      bad[conf.at<uint8_t>(y, x)] += b;
      total += 1;
      total_bad += b;
    }
  Sparsification s;
  if (total == 0) return s;
  for (int k = 1; k <= steps; ++k) {
    const double keep = total * k / steps;
    double kept = 0, kept_bad = 0;
    for (int c = 255; c >= 0 && kept < keep; --c) {
      const double take = std::min(n[static_cast<size_t>(c)], keep - kept);
      if (take <= 0) continue;
      kept += take;
      kept_bad += bad[static_cast<size_t>(c)] * take / n[static_cast<size_t>(c)];
    }
    s.curve.push_back(100.0 * kept_bad / keep);
    s.oracle.push_back(100.0 * std::max(0.0, keep - (total - total_bad)) / keep);
  }
  for (size_t k = 0; k < s.curve.size(); ++k) {
    s.auc += s.curve[k] / steps;
    s.oracle_auc += s.oracle[k] / steps;
  }
  return s;
}

cv::Mat out_to_float(const OutImage& o) {
  cv::Mat f(o.h, o.w, CV_32F);
  for (int y = 0; y < o.h; ++y)
    for (int x = 0; x < o.w; ++x) {
      const uint32_t w = o.at(x, y);
      const bool no_match = (out_fails(w) & (kFailOcc | kFailBorder)) != 0;
      f.at<float>(y, x) = out_valid(w) ? static_cast<float>(out_q4(w)) / 16.0f : no_match ? kNoMatchDisp : -1.0f;
    }
  return f;
}

FailCounts fail_counts(const OutImage& o) {
  FailCounts c;
  c.pixels = static_cast<long>(o.px.size());
  for (const uint32_t w : o.px) {
    if (out_valid(w)) continue;
    ++c.invalid;
    // the speckle bit (word bit 30) counts after the six rules of bits 29:24
    const unsigned f = out_fails(w) | ((w & kOutSpeckle) ? kFailLr << 1 : 0u);
    for (int k = 0; k < FailCounts::kN; ++k) c.by_rule[k] += f >> k & 1u;
  }
  return c;
}

std::string fail_counts_line(const FailCounts& c) {
  std::string rules;
  for (int k = 0; k < FailCounts::kN; ++k)
    if (c.by_rule[k]) rules += fmt::format("{}{} {}", rules.empty() ? ": " : ", ", FailCounts::kRules[k], c.by_rule[k]);
  return fmt::format("{} of {} pixels invalid{}", c.invalid, c.pixels, rules);
}

cv::Mat out_to_conf(const OutImage& o) {
  cv::Mat c(o.h, o.w, CV_8UC1);
  for (int y = 0; y < o.h; ++y)
    for (int x = 0; x < o.w; ++x) c.at<uint8_t>(y, x) = static_cast<uint8_t>(out_conf(o.at(x, y)));
  return c;
}

}  // namespace sm::tools
