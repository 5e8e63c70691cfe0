// Driving a disparity-stream stage (sm_post_*: s_side, s_disp, enable) one clock at a
// time, as the post-processing benches do: on a ce the beat's word (random bits on a
// virtual beat) and the enable the bench chose, on an idle clock garbage everywhere.
#pragma once

#include <random>
#include <vector>

#include "beat_schedule.hpp"
#include "post.hpp"

namespace sm::test {

// `beat` is the beat taken on this clock's ce, nullptr on an idle clock.
template <class Top>
void drive_disp(Top& top, const BeatInfo* beat, const std::vector<DispImage>& in, bool enable, std::mt19937& rng) {
  if (beat) {
    top.s_side = beat->side;
    top.s_disp = beat->frame >= 0 ? in[beat->frame].at(beat->x, beat->y) : static_cast<uint16_t>(rng());
    top.enable = enable;
  } else {  // the pipeline holds: nothing here may reach it
    top.s_side = rng() & 31;
    top.s_disp = static_cast<uint16_t>(rng());
    top.enable = rng() & 1;
  }
}

// The schedule index of every real beat: frame -> y * w + x -> beat, for the latency
// checks.
inline std::vector<std::vector<long>> beat_index(const std::vector<BeatInfo>& sched, int w,
                                                 const std::vector<int>& heights) {
  std::vector<std::vector<long>> beat_of(heights.size());
  for (size_t i = 0; i < sched.size(); ++i)
    if (sched[i].frame >= 0) {
      auto& v = beat_of[sched[i].frame];
      v.resize(static_cast<size_t>(w) * heights[sched[i].frame]);
      v[static_cast<size_t>(sched[i].y) * w + sched[i].x] = static_cast<long>(i);
    }
  return beat_of;
}

}  // namespace sm::test
