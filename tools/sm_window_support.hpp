// Window support as a confidence cue (sm_output_study --study window-conf, docs/evaluation.md
// "Wide supports in the confidence"): how many words at fixed offsets from a pixel carry a
// disparity close to its own. The stream's confidence (docs/algorithm.md 9.7) counts the
// smoothing's 5x5 window; a few samples further out, along the row and 10 rows away, see
// whether the pixel lies on a surface wider than a mismatch island. A study of what such a
// stage would buy, not a model of the RTL.
#pragma once

#include <cstdint>
#include <vector>

#include "outword.hpp"

namespace sm::tools {

struct Offset {
  int dy, dx;
};

// Per pixel of `words` (row-major, w x h), the offsets whose word lies inside the frame, is
// valid and has a Q.4 value within `tol` (1/16 px) of the pixel's own; 0 for an invalid
// pixel.
std::vector<uint16_t> offset_support(const OutImage& words, const std::vector<Offset>& offs, int tol);

// The row's samples: (0, +-step), (0, +-2 step), .. (0, +-reach).
std::vector<Offset> row_offsets(int reach, int step);

// The 3x3 grid at distance r, less its centre: (+-r or 0, +-r or 0); rows_above_only keeps
// the rows at or above the pixel's (a stage that holds r rows, no more latency).
std::vector<Offset> ring_offsets(int r, bool rows_above_only);

}  // namespace sm::tools
