// The streaming speckle check in the form the IP builds (model/speckle.hpp, the speckle
// stage: a bounded label table, the words held delay_rows rows) on the study's Q.4 maps,
// so the study can score what the table's size, the find chains and the delay cost
// against the ideal forms of sm_speckle.hpp (docs/evaluation.md, "Speckles").
#pragma once

#include <opencv2/core.hpp>

#include "speckle.hpp"

namespace sm::tools {

// q4: CV_16S disparity (negative = invalid). Returns CV_8U, 1 where a valid pixel is kept
// by sm::speckle_output at max_size, max_diff, ROWS delay_rows and LABELS labels (the maps
// carry no confidence, so no region is trusted: the size rule alone).
cv::Mat speckle_keep_table(const cv::Mat& q4, int max_size, int max_diff, int delay_rows, int labels,
                           SpeckleStats* stats = nullptr);

}  // namespace sm::tools
