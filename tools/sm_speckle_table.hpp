// The streaming speckle check in the form a folded core could build (docs/evaluation.md,
// "Speckles"): a bounded label table instead of sm_speckle.hpp's one node per pixel, so
// the study can score what the table's size, the find chains and the interleaving of
// labelling and verdicts cost against the ideal streaming form.
//
// Pixels are labelled in raster order. A pixel joins its left and upper neighbours that
// are valid and within max_diff; it takes the root of the region it joins, a new label
// from a FIFO of free labels when it joins none, and when it joins two regions the root of
// the higher rank survives (the upper one's on a tie) and the other points to it (union by
// rank: a find follows at most log2(labels) pointers). Each label counts the undecided
// pixels stored with it and the labels pointing to it, and returns to the FIFO when that
// count falls to zero. Sizes saturate at max_size + 1.
//
// Right after pixel (x, y) is labelled, pixel (x, y - delay_rows) gets its verdict: kept
// when its region's root was last reached on row y - 1 or y (it may still grow) or holds
// more than max_size pixels. The rows left at the frame's end are decided after its last
// pixel, every region then closed.
//
// When the FIFO is empty the pixel is labelled KEEP: it is kept, and so is every region
// that joins a KEEP pixel (its size saturates). So the table can only keep more than the
// ideal streaming check, never clear a pixel it keeps.
#pragma once

#include <opencv2/core.hpp>

namespace sm::tools {

struct SpeckleTableStats {
  int peak_labels = 0;   // labels in use at once, most
  int longest_find = 0;  // pointers followed by one find, most
  long keep_pixels = 0;  // pixels labelled KEEP (the table was full)
};

// q4: CV_16S disparity (negative = invalid). Returns CV_8U, 1 where a valid pixel is kept.
cv::Mat speckle_keep_table(const cv::Mat& q4, int max_size, int max_diff, int delay_rows, int labels,
                           SpeckleTableStats* stats = nullptr);

}  // namespace sm::tools
