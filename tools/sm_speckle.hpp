// The speckle check of a disparity map (sm_output_study --study speckle, docs/evaluation.md
// "Speckles: the cue that reaches the checked goal"): a connected region of valid pixels
// whose 4-neighbours differ by at most max_diff, of at most max_size pixels, is a speckle
// and becomes invalid. With the whole frame at hand this is OpenCV's filterSpeckles. A
// streaming core can only decide row y once it has seen rows up to y + delay_rows, so the
// study also scores that form: the region is the one the rows seen so far connect, and a
// region that still reaches the newest row is kept (it may yet grow).
#pragma once

#include <opencv2/core.hpp>

namespace sm::tools {

// Whether pixel (x, y) of q4 joins its left and its upper neighbour: both valid (>= 0) and
// within max_diff of it. The one neighbour test of every form of the check.
struct Joins {
  bool left = false, up = false;
};
Joins joins(const cv::Mat& q4, int y, int x, int max_diff);

// q4: CV_16S disparity (any unit; negative = invalid). Returns CV_8U, 1 where a valid pixel
// is kept, 0 elsewhere. delay_rows >= rows: the whole frame (cv::filterSpeckles' verdict).
cv::Mat speckle_keep(const cv::Mat& q4, int max_size, int max_diff, int delay_rows);

// What the streaming form must hold at once, the peak over the frame of the rows still
// awaiting their verdict (rows newest - delay_rows .. newest): `regions`, the distinct
// regions their valid pixels belong to (a table that relabels on every merge needs one
// entry each); `labels`, the distinct labels they were given when labelled, before the
// merges that came after (a table that keeps merged labels as pointers, as sm_objects
// does, needs one entry each).
struct SpeckleHold {
  int regions = 0, labels = 0;
};
SpeckleHold speckle_hold(const cv::Mat& q4, int max_diff, int delay_rows);

}  // namespace sm::tools
