#include "sm_host_speckle.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
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

namespace {

// "SIZE" or "SIZE,DIFF" split at the comma; nullopt for any other shape.
std::optional<std::pair<std::string, std::string>> split_spec(const std::string& s) {
  const size_t comma = s.find(',');
  if (comma == std::string::npos) return std::pair{s, std::string{}};
  if (s.find(',', comma + 1) != std::string::npos || comma + 1 == s.size()) return std::nullopt;
  return std::pair{s.substr(0, comma), s.substr(comma + 1)};
}

// SIZE 0..kMaxSize and an optional DIFF 0..255, in int_in's wording.
CLI::Validator speckle_spec() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const auto parts = split_spec(s);
        if (!parts) return fmt::format("'{}': expected SIZE or SIZE,DIFF", s);
        std::string size = parts->first, diff = parts->second;
        std::string e = int_in(0, kMaxSize)(size);
        if (e.empty() && !diff.empty()) e = int_in(0, 255)(diff);
        return e;
      },
      fmt::format("SIZE in 0..{}, DIFF in 0..255", kMaxSize));
}

}  // namespace

void HostSpeckleOptions::add(CLI::App& app) {
  app.add_option_function<std::string>(
         "--speckle",
         [this](const std::string& s) {
           const auto parts = split_spec(s);  // checked by speckle_spec()
           max_size = std::stoi(parts->first);
           max_diff = parts->second.empty() ? kHostSpeckleDiff : std::stoi(parts->second);
         },
         fmt::format("host-side speckle check on the disparity before any output: regions of at most SIZE pixels "
                     "whose 4-neighbours differ by at most DIFF/16 px become invalid (OpenCV filterSpeckles; DIFF "
                     "default {}; {},{} with --lr-en 0 --agree-en 0 --smooth-en 0 is the host recipe of "
                     "docs/evaluation.md, \"Speckles\")",
                     kHostSpeckleDiff, kHostSpeckleSize, kHostSpeckleDiff))
      ->type_name("SIZE[,DIFF]")
      ->check(speckle_spec());
}

std::string HostSpeckleOptions::describe() const {
  return fmt::format("speckles of at most {} px within {}/16 px", max_size, max_diff);
}

}  // namespace sm::tools
