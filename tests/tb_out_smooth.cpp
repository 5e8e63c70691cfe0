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
#include "sm_block_test.hpp"
#include "smooth.hpp"
#include "speckle.hpp"

using namespace sm;
using namespace sm::test;

namespace {

// Slanted planes a few levels apart with +-thr noise in the Q.4 value, a tenth invalid,
// now and then a word anywhere in 0 .. 16 (DISP - 1) (frame 1: anywhere everywhere).
OutImage random_words(std::mt19937& rng, int w, int h, int nd, bool anywhere) {
  OutImage m(w, h);
  const int top = 16 * (nd - 1);
  const int step = 16 * (1 + static_cast<int>(rng() % 4));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int base = (x * 3 / std::max(1, w / 4)) * step + y * 2 + static_cast<int>(rng() % 70) - 35;
      const int q = anywhere || rng() % 12 == 0 ? static_cast<int>(rng() % (top + 1)) : std::clamp(base, 0, top);
      const bool valid = rng() % 10 != 0;
      const unsigned byte = rng() & 0xff;  // the confidence, or an invalid word's failed rules
      // an invalid word: its failed rules, now and then the speckle stage's bit (9.8)
      m.at(x, y) =
          make_out_word(valid, byte, static_cast<unsigned>(q), byte) | (!valid && (byte & 64) ? kOutSpeckle : 0);
    }
  return m;
}

}  // namespace

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
      in.push_back(random_words(rng, w, heights[f], hw.disp, f == 1));
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
      const uint32_t e = want[o->frame].at(o->x, o->y);
      const long lat = static_cast<long>(k - 1) - beat_of[o->frame][static_cast<size_t>(o->y) * w + o->x];
      if (lat != latency)
        t.fail(fmt::format("latency at w {} frame {} x {} y {}: {} beats, documented {}", w, o->frame, o->x, o->y, lat,
                           latency));
      else
        t.check(tb->m_word == e, [&] {
          return fmt::format("w {} frame {} x {} y {} expected {:#010x} got {:#010x}", w, o->frame, o->x, o->y, e,
                             tb->m_word);
        });
    }
    t.all_out();
    frames += static_cast<int>(heights.size());
  }
  return t.finish(fmt::format("tb_out_smooth MAX_WIDTH={} DISP={} widths {} ({} frames)", hw.max_width, hw.disp,
                              widths.size(), frames));
}
