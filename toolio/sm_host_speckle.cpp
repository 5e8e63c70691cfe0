#include "sm_host_speckle.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "sm_cli.hpp"

namespace sm::tools {

namespace {
// filterSpeckles' value for invalid pixels: below every valid Q.4 value, and what it
// paints the cleared pixels with.
constexpr int16_t kInvalidQ4 = -16;
// A bound far above any frame the IP takes (MAX_WIDTH x MAX_HEIGHT), so a typo is caught.
constexpr int kMaxSize = 1 << 24;
}  // namespace

long host_speckle(cv::Mat& disp_f, int max_size, int max_diff) {
  CV_Assert(disp_f.type() == CV_32F);
  if (max_size <= 0) return 0;
  cv::Mat q4(disp_f.size(), CV_16S);
  for (int y = 0; y < disp_f.rows; ++y)
    for (int x = 0; x < disp_f.cols; ++x) {
      const float d = disp_f.at<float>(y, x);
      const bool valid = std::isfinite(d) && d >= 0 && d * 16.0f <= 32767.0f;
      q4.at<int16_t>(y, x) = valid ? static_cast<int16_t>(std::lround(d * 16.0f)) : kInvalidQ4;
    }
  const cv::Mat before = q4.clone();
  cv::filterSpeckles(q4, kInvalidQ4, max_size, max_diff);
  long cleared = 0;
  for (int y = 0; y < disp_f.rows; ++y)
    for (int x = 0; x < disp_f.cols; ++x)
      if (q4.at<int16_t>(y, x) != before.at<int16_t>(y, x)) {
        disp_f.at<float>(y, x) = -1.0f;
        ++cleared;
      }
  return cleared;
}

void HostSpeckleOptions::add(CLI::App& app) {
  app.add_option("--speckle", size_diff,
                 fmt::format("host-side speckle check on the disparity before any output: regions of at most SIZE "
                             "pixels whose 4-neighbours differ by at most DIFF/16 px become invalid (OpenCV "
                             "filterSpeckles; DIFF default {}; {},{} with --lr-en 0 --agree-en 0 --smooth-en 0 is "
                             "the host recipe of docs/evaluation.md, \"Speckles\")",
                             kHostSpeckleDiff, kHostSpeckleSize, kHostSpeckleDiff))
      ->type_name("SIZE[,DIFF]")
      ->delimiter(',')
      ->expected(1, 2)
      ->check(int_in(0, kMaxSize).application_index(0))
      ->check(int_in(0, 255).application_index(1));
}

std::string HostSpeckleOptions::describe() const {
  return fmt::format("speckles of at most {} px within {}/16 px", size(), diff());
}

}  // namespace sm::tools
