// Block test of sm_out_support (the row support of the stream's confidence, docs/algorithm.md
// 9.7) against the model's row_support_output: frames of surfaces (slanted planes with
// noise in the fraction), depth steps, invalid words and words of random levels and
// confidences (up to 255: the sum saturates), back to back at odd widths (rows shorter
// than the samples' reach too: the stage tells rows apart by their sol), then virtual
// rows, with random ce gaps and garbage on idle beats.
// Every real output word and its latency are checked.
#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "disp_stream.hpp"
#include "out_word_bench.hpp"
#include "row_support.hpp"
#include "sm_block_test.hpp"

using namespace sm;
using namespace sm::test;

int main(int argc, char** argv) {
  BlockTest<SM_VTOP> t{"row support block test"};
  const HwConfig hw = verilated_config();
  std::vector<int> widths = {37, 16, 64};
  int h = 9;
  t.option("--widths", widths, "active widths, one frame group each").delimiter(',').range(1, hw.max_width);
  t.option("--height", h, "rows of the first frame (the others: +2, -1, +1, ...)").range(2, 4096);
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(2468);
  auto& tb = t.tb();
  tb->ce = 1;
  tb->s_side = 0;
  t.reset(3);
  t.ce_schedule(91, 30);
  int frames = 0;
  for (const int w : widths) {
    const std::vector<int> heights = {h, h + 2, 1, h + 1, 3};
    std::vector<OutImage> in, want;
    for (size_t f = 0; f < heights.size(); ++f) {
      in.push_back(random_out_words(rng, w, heights[f], hw.disp, f == 1, 25));
      want.push_back(row_support_output(in.back()));
    }
    const auto sched = make_schedule(w, heights, 6);
    const long latency = kRowSupportReach + 2;  // documented in sm_out_support.v
    const auto beat_of = beat_index(sched, w, heights);
    t.expect_frames(w, heights);
    size_t k = 0;
    while (k < sched.size()) {
      const bool c = t.next_ce();
      const BeatInfo* b = c ? &sched[k++] : nullptr;
      if (b) {
        tb->s_side = b->side;
        tb->s_word = b->frame >= 0 ? in[b->frame].at(b->x, b->y) : static_cast<uint32_t>(rng());
      } else {  // the pipeline holds: nothing here may reach it
        tb->s_side = rng() & 31;
        tb->s_word = static_cast<uint32_t>(rng());
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
  return t.finish(fmt::format("tb_out_support MAX_WIDTH={} DISP={} widths {} ({} frames)", hw.max_width, hw.disp,
                              widths.size(), frames));
}
