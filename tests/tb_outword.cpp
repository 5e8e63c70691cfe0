// Block test of sm_outword (the output word after the post filters, docs/algorithm.md 9.6)
// against the model's out_word: frames of random fields and post levels -- the filters'
// level equal to the DP's, one off, or anywhere; the background fill absent, below or
// above it; offsets over the whole -24..24; pixels near the left border -- back to back
// at odd widths, then virtual rows, with random ce gaps and garbage on idle beats. Every
// real output word is compared, and its latency (out after the next ce) is checked.
#include <fmt/format.h>

#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "disp_stream.hpp"
#include "out_fields_bits.hpp"
#include "outword.hpp"
#include "sm_block_test.hpp"

using namespace sm;
using namespace sm::test;

namespace {

struct Pixel {
  OutFields f;
  DispPix post = 0;
};

int level_near(std::mt19937& rng, int d, int nd) {
  switch (rng() % 4) {
    case 0:
      return static_cast<int>(rng() % nd);
    case 1:
      return std::clamp(d + static_cast<int>(rng() % 3) - 1, 0, nd - 1);
    default:
      return d;  // the filters kept the DP's level (the common case)
  }
}

Pixel random_pixel(std::mt19937& rng, int x, int nd) {
  Pixel p;
  // levels near the column now and then, so x < d_out happens on both sides of it
  const int d = rng() % 3 == 0 ? std::min(nd - 1, x + static_cast<int>(rng() % 3) - 1) : static_cast<int>(rng() % nd);
  p.f.d = static_cast<uint8_t>(std::max(0, d));
  p.f.off = static_cast<int8_t>(static_cast<int>(rng() % 49) - 24);
  p.f.fail = rng() % 5 == 0;
  p.f.border_en = rng() % 4 != 0;
  p.f.lr_ok = rng() & 1;
  p.f.matched = rng() & 1;
  p.f.agree_ok = rng() & 1;
  p.f.ratio = static_cast<uint8_t>(rng() % 32);
  p.f.fb = static_cast<uint8_t>(rng() % 2 ? nd - 1 : level_near(rng, p.f.d, nd));
  p.post = make_disp(static_cast<unsigned>(level_near(rng, p.f.d, nd)), rng() % 10 != 0);
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  const HwConfig hw = verilated_config();
  BlockTest<SM_VTOP> t{"sm_outword block test"};
  std::vector<int> widths{37};
  int h = 9;
  t.option("--widths", widths, "active widths, one frame group each").delimiter(',').range(2, hw.max_width);
  t.option("--height", h, "rows of the frames").range(1, 4096);
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int dw = sm::clog2(hw.disp);
  std::mt19937 rng(0x0a7d + hw.disp);

  auto& tb = t.tb();
  tb->ce = 1;
  tb->s_side = 0;
  t.reset(3);
  t.ce_schedule(17 + hw.disp, 30);
  for (const int w : widths) {
    const std::vector<int> heights = {h, 1, h + 2};
    std::vector<std::vector<Pixel>> in(heights.size());
    for (size_t f = 0; f < heights.size(); ++f)
      for (int i = 0; i < w * heights[f]; ++i) in[f].push_back(random_pixel(rng, i % w, hw.disp));
    const auto sched = make_schedule(w, heights, 1);
    const auto beat_of = beat_index(sched, w, heights);
    t.expect_frames(w, heights);
    const std::string where = fmt::format("width {}: ", w);
    size_t k = 0;
    while (k < sched.size()) {
      const bool c = t.next_ce();
      if (c) {
        const BeatInfo& b = sched[k++];
        tb->s_side = b.side;
        const Pixel* p = b.frame >= 0 ? &in[b.frame][static_cast<size_t>(b.y) * w + b.x] : nullptr;
        tb->s_disp = p ? p->post : static_cast<uint16_t>(rng());
        tb->s_fields = p ? pack_fields(p->f, dw) : static_cast<uint32_t>(rng());
      } else {  // garbage the block must not take
        tb->s_side = rng() & 31;
        tb->s_disp = static_cast<uint16_t>(rng());
        tb->s_fields = static_cast<uint32_t>(rng());
      }
      tb.tick();
      if (!c || !(tb->m_side & kReal)) continue;
      const auto o = t.next_out(tb->m_side, where);
      if (!o) break;
      const size_t pix = static_cast<size_t>(o->y) * w + o->x;
      const Pixel& p = in[o->frame][pix];
      const long lat = static_cast<long>(k - 1) - beat_of[o->frame][pix];
      if (lat != 1) {
        t.fail(
            fmt::format("{}latency at frame {} x {} y {}: {} beats, documented 1", where, o->frame, o->x, o->y, lat));
        continue;
      }
      const uint32_t want = out_word(p.f, p.post, o->x, hw.disp);
      t.check(tb->m_word == want, [&] {
        return fmt::format(
            "{}frame {} x {} y {}: d {} off {} fb {} post {:#06x} fail {} border_en {}: word {:#010x}, "
            "model {:#010x}",
            where, o->frame, o->x, o->y, p.f.d, p.f.off, p.f.fb, p.post, p.f.fail, p.f.border_en, tb->m_word, want);
      });
    }
    t.all_out(where);
  }
  return t.finish(fmt::format("tb_outword DISP={}", hw.disp));
}
