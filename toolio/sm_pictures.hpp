// Pictures that explain themselves (issue 42): disparity in colour over the data's own
// range with a colour bar (disparity ticks, and depth ticks when a camera is known),
// invalid pixels in one colour named in a legend, the error map with its legend, object
// boxes labelled with the report's IDs and the frame's flags, and a bird's-eye view of
// the point cloud. All images are 8-bit BGR. Used by stereo_model (--colour, --cloud-view)
// and meant for stereo_sim's panel.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "calib_file.hpp"
#include "post.hpp"
#include "sm_depth.hpp"

namespace sm::tools {

// Invalid (no estimate) in every disparity picture: white, which the turbo map never is;
// grey where no match exists (occluded or left of the border: kNoMatchDisp, sm_metrics.hpp).
const cv::Scalar kInvalidColour(255, 255, 255);
const cv::Scalar kNoMatchColour(128, 128, 128);
// The error map's classes (BGR).
const cv::Scalar kGoodColour(0, 160, 0);        // within 1 px of the ground truth
const cv::Scalar kBadColour(0, 0, 255);         // off by more than 1 px
const cv::Scalar kNoEstColour(255, 0, 255);     // no estimate where the truth is known
const cv::Scalar kNotScoredColour(40, 40, 40);  // unknown truth or occluded

// The disparity range a picture spans.
struct ColourRange {
  double lo = 0, hi = 1;
};
// min..max of the valid disparities (finite, >= 0); 0..1 when there is none, and
// hi = lo + 1 when all are equal.
ColourRange data_range(const cv::Mat& disp_f);

// Turbo colour map over r (lo = dark blue, hi = dark red, clamped), invalid (negative or
// non-finite) = kInvalidColour, kNoMatchDisp = kNoMatchColour. Replaces disp_to_colour(d, levels) when the range should
// follow the data: disp_to_colour(d, L) is colourise(d, {0, L - 1}) within one step of the
// colour map (it maps disparity 0..L-1 over grey 1..255, disp_to_grey) except the invalid
// colour (black there).
cv::Mat colourise(const cv::Mat& disp_f, ColourRange r);

// A vertical colour bar `height` rows tall for r (hi at the top): disparity ticks on its
// left, depth ticks in metres on its right when `cam` is given, and under it the invalid
// swatches, "hidden" (no match: occluded or left of the border) and "invalid" (rejected
// by a check).
cv::Mat colour_bar(ColourRange r, int height, const RectCamera* cam = nullptr);
// colourise(disp_f, r) with colour_bar(r, rows, cam) on its right.
cv::Mat disparity_picture(const cv::Mat& disp_f, ColourRange r, const RectCamera* cam = nullptr);

// `img` with a legend strip under it: one colour swatch and its name per entry.
cv::Mat with_legend(const cv::Mat& img, const std::vector<std::pair<cv::Scalar, std::string>>& entries);

// Error map against ground truth (gt > 0 known; mask 0 = not scored, may be empty):
// kGoodColour, kBadColour, kNoEstColour, kNotScoredColour (stereo_sim's error_map()).
cv::Mat error_map(const cv::Mat& est, const cv::Mat& gt, const cv::Mat& mask);
// error_map with its legend (green good, red bad, magenta invalid, grey not scored).
cv::Mat error_map_picture(const cv::Mat& est, const cv::Mat& gt, const cv::Mat& mask);

// The boxes of `objects` drawn on a copy of `bgr`, each labelled with its index in the
// list ("#0", "#1", ... as in report.json / --objects-json), and the frame's flags
// ("TOO-MANY", "TABLE-FULL") in the bottom-left corner when set.
cv::Mat draw_objects(const cv::Mat& bgr, const std::vector<Object>& objects, bool too_many, bool table_full);

// The tiles side by side, each padded at the bottom with black to the tallest one (a tile
// with a legend strip next to one without); grey tiles are converted to BGR.
cv::Mat side_by_side(const std::vector<cv::Mat>& tiles);

// `img` with `label` in its top-left corner, white on black (stereo_sim's labelled()).
cv::Mat labelled(const cv::Mat& img, const std::string& label);

// Bird's-eye view of a point cloud (looking down the camera's Y axis): X across, Z up the
// picture (the camera at the bottom centre), points coloured by their grey value, a
// grid every "nice" metre step with labels. z_max <= 0: the 99th percentile of Z.
cv::Mat cloud_view(const std::vector<CloudPoint>& points, cv::Size size, double z_max = 0);

}  // namespace sm::tools
