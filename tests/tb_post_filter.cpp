// Block test of one post-processing filter (--filter vmed, med3 or med53; docs/algorithm.md
// section 7): frames of random and structured disparity maps, back to back, random ce
// gaps with garbage on idle and virtual beats, the enable switched per frame; every real
// output pixel is compared with the model.
#include <fmt/format.h>

#include <map>
#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "disp_stream.hpp"
#include "sm_block_test.hpp"

using namespace sm;
using namespace sm::test;

namespace {
DispImage random_map(std::mt19937& rng, int w, int h, int dlo, int dhi, int invalid_pct) {
  DispImage m(w, h);
  for (auto& p : m.px) {
    const bool valid = static_cast<int>(rng() % 100) >= invalid_pct;
    // a quarter of the valid words carry junk above every level (bits 9..14; DISP <= 254),
    // which the filters ignore and drop
    const unsigned junk = (rng() % 4 == 0) ? (rng() & 0x7e00) : 0;
    const unsigned d = valid ? (dlo + rng() % (dhi - dlo + 1)) | junk : rng() & 0x7fff;
    p = make_disp(d, valid);
  }
  return m;
}
// Background, two boxes, and one-row streaks of a wrong disparity.
DispImage structured_map(std::mt19937& rng, int w, int h, int disp) {
  DispImage m(w, h, make_disp(2, true));
  for (int y = h / 4; y < h / 2 + 1; ++y)
    for (int x = w / 5; x < w / 2; ++x) m.at(x, y) = make_disp(disp / 2, true);
  for (int y = h / 2; y < h; ++y)
    for (int x = w / 2 + 3; x < w - 2; ++x) m.at(x, y) = make_disp(disp - 1, true);
  for (int s = 0; s < 4; ++s) {
    const int y = rng() % h, x0 = rng() % w, len = 3 + rng() % 12;
    const unsigned d = rng() % disp;
    for (int x = x0; x < std::min(w, x0 + len); ++x) m.at(x, y) = make_disp(d, true);
  }
  m.at(0, 0) = 0;  // an invalid corner
  return m;
}
}  // namespace

int main(int argc, char** argv) {
  BlockTest<SM_VTOP> t{"post-processing filter block test"};
  const HwConfig hw = verilated_config();
  int w = 37, h = 9;
  // the filter's number (1..3) also offsets the seeds: each filter has its own stimulus
  int filter = 0;
  const std::map<std::string, int> filters{{"vmed", 1}, {"med3", 2}, {"med53", 3}};
  t.option("--filter", filter, "the model's filter, as the Verilated shape: vmed, med3 or med53")
      .required()
      .names(filters);
  t.option("--width", w, "active width").range(2, hw.max_width);
  t.option("--height", h, "rows of the first frame (the others: +2, -1, +1)").range(2, 4096);
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(1234 + filter);
  const std::vector<int> heights = {h, h + 2, h - 1, h + 1};
  const std::vector<bool> enable = {true, true, false, true};
  std::vector<DispImage> in, want;
  for (size_t f = 0; f < heights.size(); ++f) {
    DispImage m =
        (f % 2 == 0) ? random_map(rng, w, heights[f], 0, hw.disp - 1, 10) : structured_map(rng, w, heights[f], hw.disp);
    if (f == 2) m = random_map(rng, w, heights[f], 3, 6, 20);  // many ties
    DispImage out = post_bypass(m, hw);                        // disabled: the valid bit and the disparity
    if (enable[f]) {
      if (filter == 1) out = post_vmedian(m, hw);
      if (filter == 2) out = post_median3(m, hw);
      if (filter == 3) out = post_median53(m, hw);
    }
    in.push_back(m);
    want.push_back(out);
  }
  const auto sched = make_schedule(w, heights, 4);
  // documented latency (docs/algorithm.md section 7): RY*W + RX + 2 beats
  const int ry = filter == 2 ? 1 : 2, rx = filter == 1 ? 0 : 1;
  const long latency = static_cast<long>(ry) * w + rx + 2;
  const auto beat_of = beat_index(sched, w, heights);

  auto& tb = t.tb();
  tb->ce = 1;
  tb->width = w;
  tb->s_side = 0;
  t.reset(3);

  t.ce_schedule(77 + filter, 30);
  t.expect_frames(w, heights);
  bool cur_en = true;
  size_t k = 0;
  while (k < sched.size()) {
    const bool c = t.next_ce();
    const BeatInfo* b = c ? &sched[k++] : nullptr;
    if (b && b->frame >= 0 && b->x == 0 && b->y == 0) cur_en = enable[b->frame];
    drive_disp(tb.top(), b, in, cur_en, rng);
    tb.tick();
    if (!c || !(tb->m_side & kReal)) continue;
    const auto o = t.next_out(tb->m_side);
    if (!o) break;
    const uint16_t e = want[o->frame].at(o->x, o->y);
    const size_t pix = static_cast<size_t>(o->y) * w + o->x;
    const long lat = static_cast<long>(k - 1) - beat_of[o->frame][pix];  // beats since entry
    if (lat != latency)
      t.fail(fmt::format("latency at frame {} x {} y {}: {} beats, documented {}", o->frame, o->x, o->y, lat, latency));
    else
      t.check(tb->m_disp == e, [&] {
        return fmt::format("frame {} x {} y {} expected {:#06x} got {:#06x}", o->frame, o->x, o->y, e, tb->m_disp);
      });
  }
  t.all_out();
  return t.finish(fmt::format("tb_post_filter {} MAX_WIDTH={} DISP={} W={}", filter, hw.max_width, hw.disp, w));
}
