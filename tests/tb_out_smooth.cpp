// Block test of sm_out_smooth (the output words' smoothing, docs/algorithm.md 9.7) against
// the model's smooth_output: frames of surfaces (planes with noise in the fraction), depth
// steps, invalid pixels and words of random levels, back to back at odd widths, then
// virtual rows, with random ce gaps and garbage on idle beats. The enable and the
// threshold change per frame (0, the default, the greatest); every real output word and
// its latency are checked.
#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "disp_stream.hpp"
#include "out_word_bench.hpp"
#include "sm_block_test.hpp"
#include "smooth.hpp"

using namespace sm;
using namespace sm::test;

int main(int argc, char** argv) {
  BlockTest<SM_VTOP> t{"output smoothing block test"};
  const HwConfig hw = verilated_config();
  std::vector<int> widths = {37, 5, 64};
  int h = 9;
  t.option("--widths", widths, "active widths, one frame group each").delimiter(',').range(3, hw.max_width);
  t.option("--height", h, "rows of the first frame (the others: +2, -1, +1, ...)").range(2, 4096);
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(4321);
  auto& tb = t.tb();
  tb->ce = 1;
  tb->s_side = 0;
  t.reset(3);
  t.ce_schedule(91, 30);
  // (enable, thr) per frame: the default, off, the greatest, only equal values, one pixel
  const int en[] = {1, 0, 1, 1, 1};
  const int thr[] = {24, 24, 63, 0, 16};
  int frames = 0;
  for (const int w : widths) {
    tb->width = w;
    const std::vector<int> heights = {h, h + 2, 1, h + 1, 3};
    std::vector<OutImage> in, want;
    for (size_t f = 0; f < heights.size(); ++f) {
      in.push_back(random_out_words(rng, w, heights[f], hw.disp, f == 1, 35));
      want.push_back(smooth_output(in.back(), en[f], thr[f]));
    }
    const auto sched = make_schedule(w, heights, 6);
    const long latency = 2L * w + 2 + 5;  // documented in sm_out_smooth.v
    const auto beat_of = beat_index(sched, w, heights);
    t.expect_frames(w, heights);
    int cur = 0;
    size_t k = 0;
    while (k < sched.size()) {
      const bool c = t.next_ce();
      // the settings of the frame whose pixel is the centre the block takes them with: the
      // beat that entered latency - 5 beats before the previous one
      const long j = static_cast<long>(k) - 1 - (latency - 5);
      if (c && j >= 0 && sched[static_cast<size_t>(j)].frame >= 0) cur = sched[static_cast<size_t>(j)].frame;
      const BeatInfo* b = c ? &sched[k++] : nullptr;
      if (b) {
        tb->s_side = b->side;
        tb->s_word = b->frame >= 0 ? in[b->frame].at(b->x, b->y) : static_cast<uint32_t>(rng());
        tb->enable = en[cur];
        tb->thr = thr[cur];
      } else {  // the pipeline holds: nothing here may reach it
        tb->s_side = rng() & 31;
        tb->s_word = static_cast<uint32_t>(rng());
        tb->enable = rng() & 1;
        tb->thr = rng() & 63;
      }
      tb.tick();
      if (!c || !(tb->m_side & kReal)) continue;
      const auto o = t.next_out(tb->m_side);
      if (!o) break;
      check_out_word(t, *o, k, beat_of, w, latency, want, tb->m_word);
    }
    t.all_out();
    frames += static_cast<int>(heights.size());
  }
  return t.finish(fmt::format("tb_out_smooth MAX_WIDTH={} DISP={} widths {} ({} frames)", hw.max_width, hw.disp,
                              widths.size(), frames));
}
