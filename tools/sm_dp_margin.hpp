// The trellis's own margin as a confidence cue (sm_output_study --study dp-margin,
// docs/evaluation.md "The trellis's margin"): min-marginals of one line's trellis
// (docs/algorithm.md 6), from a forward and a backward pass. The core's sm_dp runs the
// forward pass only; the backward one would be a second trellis, so this is a study of
// what that trellis would buy, not a model of the RTL.
#pragma once

#include <cstdint>
#include <vector>

namespace sm::tools {

// No path matches the pixel at that level (the level exceeds what the line allows).
constexpr int64_t kNoPath = INT64_MAX / 4;

// M(x, d) at [x * disp + d], x = 0..n-1: the cost of the cheapest path that matches left
// pixel x at level d, minus the cost of the optimal path (so >= 0, and 0 on the optimal
// path's matched nodes), or kNoPath. agg, n and pen as trellis_line_pen's (pen: n + 1
// penalties, one per left pixel of the occlusion nodes).
std::vector<int64_t> dp_min_marginals(const uint8_t* agg, int n, const uint8_t* pen, int disp);

// What the forward pass alone knows, in dp_min_marginals' layout: E(x, d) at [x * disp + d],
// the cost of the cheapest path from (0, 0) to the node matching left pixel x at level d
// (site 2x + 1 - d) less the cheapest path to any node of that site, or kNoPath. sm_dp
// holds these costs at each site; a cue built on them needs no second trellis.
std::vector<int64_t> dp_forward_excess(const uint8_t* agg, int n, const uint8_t* pen, int disp);

// Both of the above from one forward pass (the study scores both cues per frame).
struct LineMargins {
  std::vector<int64_t> min_marginal, forward_excess;
};
LineMargins dp_line_margins(const uint8_t* agg, int n, const uint8_t* pen, int disp);

// The margin of level d at one pixel (m: its disp min-marginals): the cheapest match two
// levels or more away from d, less the cheapest within one level of d; a large margin means
// no other surface along the row comes close. -kNoPath when no path matches the pixel
// within one level of d (d is out of the line's reach there, as at the left border x < d),
// else kNoPath when none matches it two levels or more away.
int64_t dp_margin(const int64_t* m, int disp, int d);

}  // namespace sm::tools
