// Block test of sm_outfields (the output stage's first half, at the DP's read-out,
// docs/algorithm.md 9.6) against the model's out_fields: frames of random evidence --
// the DP's level at, next to and away from the WTA level, both at the level range's ends,
// runs with gaps above and below the threshold, x < d on the left (lr then reads as
// 255 whatever the store gives) -- with a random register set on every beat (the block
// registers it with the beat), SUBPIX 0, 1 and 2, both fits, every rule on and off.
// Random ce gaps with garbage on the idle clocks; every real output's fields compared,
// and their latency (out 9 ce's after the ce that takes the beat in) checked.
#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "disp_stream.hpp"
#include "out_fields_bits.hpp"
#include "sm_block_test.hpp"

using namespace sm;
using namespace sm::test;

namespace {

int level(std::mt19937& rng, int nd) {
  switch (rng() % 5) {
    case 0:
      return 0;
    case 1:
      return nd - 1;
    default:
      return static_cast<int>(rng() % nd);
  }
}

// One pixel of evidence with the model's invariants: c1 the least cost (band[2] = c1),
// c2 and cmax not below it, the band 0 outside the level range.
void random_evidence(std::mt19937& rng, Evidence& ev, int x, int y, int nd, int cmax_v) {
  const int dw = level(rng, nd);
  const int d = rng() % 2 ? std::clamp(dw + static_cast<int>(rng() % 3) - 1, 0, nd - 1) : level(rng, nd);
  const int c1 = static_cast<int>(rng() % (cmax_v + 1));
  auto above = [&](int lo) { return lo + static_cast<int>(rng() % (cmax_v - lo + 1)); };
  ev.dw.at(x, y) = static_cast<uint8_t>(dw);
  ev.d.at(x, y) = static_cast<uint8_t>(d);
  ev.c1.at(x, y) = static_cast<uint8_t>(c1);
  ev.c2.at(x, y) = static_cast<uint8_t>(rng() % 4 == 0 ? c1 : above(c1));
  ev.cmax.at(x, y) = static_cast<uint8_t>(std::max<int>(ev.c2.at(x, y), above(c1)));
  for (int j = 0; j < 5; ++j) {
    const int k = dw - 2 + j;
    ev.band[static_cast<size_t>(j)].at(x, y) = static_cast<uint8_t>(k < 0 || k >= nd ? 0
                                                                    : j == 2         ? c1
                                                                    : rng() % 3 == 0 ? c1
                                                                                     : above(c1));
  }
  ev.matched.at(x, y) = rng() & 1;
  ev.gap.at(x, y) = ev.matched.at(x, y) ? 0 : static_cast<uint8_t>(rng() % 4 == 0 ? 255 : rng() % 6);
  ev.fill_bg.at(x, y) = static_cast<uint8_t>(ev.matched.at(x, y) ? d : level(rng, nd));
  const int lr = rng() % 2 ? std::clamp(d + static_cast<int>(rng() % 7) - 3, 0, nd - 1) : level(rng, nd);
  ev.lr.at(x, y) = static_cast<uint8_t>(x < d ? 255 : lr);
}

OutputRegs random_regs(std::mt19937& rng) {
  OutputRegs r;
  r.subpix_en = rng() % 5 != 0;
  r.subpix_src = static_cast<uint8_t>(1 + rng() % 2);  // the RTL's sources (0 is model-only)
  r.subpix_fit = rng() & 1;
  r.occ_en = rng() & 1;
  r.fill_bg = rng() & 1;
  r.lr_en = rng() & 1;
  r.agree_en = rng() & 1;
  r.uniq_en = rng() & 1;
  r.tex_en = rng() & 1;
  auto t = [&] { return static_cast<uint8_t>(rng() % 8 == 0 ? rng() % 256 : rng() % 5); };
  r.occ_t = t();
  r.lr_t = t();
  r.agree_t = t();
  r.uniq_t = t();
  r.tex_t = t();
  return r;
}

struct Frame {
  Evidence ev;
  std::vector<OutputRegs> regs;
  std::vector<uint32_t> lr_store;  // what the right-WTA store gives (garbage where x < d)
};

}  // namespace

int main(int argc, char** argv) {
  const HwConfig hw = verilated_config();
  const int cw = SM_P_CW;
  BlockTest<SM_VTOP> t{"sm_outfields block test"};
  int w = 37, h = 9;
  t.option("--width", w, "row width").range(2, hw.max_width);
  t.option("--height", h, "rows per frame").range(1, 4096);
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int dw = sm::clog2(hw.disp);
  std::mt19937 rng(0xf1e1d + hw.disp);
  const std::vector<int> heights{h, 1, h + 1};
  std::vector<Frame> frames;
  for (const int fh : heights) {
    Frame f{Evidence(w, fh), {}, {}};
    for (int y = 0; y < fh; ++y)
      for (int x = 0; x < w; ++x) {
        random_evidence(rng, f.ev, x, y, hw.disp, (1 << cw) - 1);
        f.regs.push_back(random_regs(rng));
        f.lr_store.push_back(f.ev.lr.at(x, y) == 255 ? rng() % hw.disp : f.ev.lr.at(x, y));
      }
    frames.push_back(std::move(f));
  }
  auto& tb = t.tb();
  tb->ce = 1;
  tb->s_side = 0;
  t.reset(3);
  t.ce_schedule(23 + hw.disp, 30);
  const auto sched = make_schedule(w, heights, 1);
  const auto beat_of = beat_index(sched, w, heights);
  t.expect_frames(w, heights);
  size_t k = 0;
  while (k < sched.size()) {
    const bool c = t.next_ce();
    const BeatInfo* b = c ? &sched[k++] : nullptr;
    const bool real = b && b->frame >= 0;
    const Frame* f = real ? &frames[static_cast<size_t>(b->frame)] : nullptr;
    const size_t pix = real ? static_cast<size_t>(b->y) * w + b->x : 0;
    auto e8 = [&](Image8 Evidence::*m, unsigned mask) -> uint32_t {
      return real ? (f->ev.*m).at(b->x, b->y) : rng() & mask;
    };
    const unsigned dm = (1u << dw) - 1, cm = (1u << cw) - 1;
    tb->s_side = b ? b->side : rng() & 31;
    tb->s_x = b ? b->x : rng() % w;
    tb->s_d = e8(&Evidence::d, dm);
    tb->s_matched = e8(&Evidence::matched, 1);
    tb->s_gap = e8(&Evidence::gap, 255);
    tb->s_fill_bg = e8(&Evidence::fill_bg, dm);
    tb->s_dw = e8(&Evidence::dw, dm);
    tb->s_c1 = e8(&Evidence::c1, cm);
    tb->s_c2 = e8(&Evidence::c2, cm);
    tb->s_cmax = e8(&Evidence::cmax, cm);
    uint64_t band = 0;
    for (int j = 4; j >= 0; --j)
      band = band << cw | (real ? f->ev.band[static_cast<size_t>(j)].at(b->x, b->y) : rng() & cm);
    tb->s_band = band;
    tb->s_lr = real ? f->lr_store[pix] : rng() & dm;
    tb->s_cfg = real ? pack_cfg(f->regs[pix]) : (static_cast<uint64_t>(rng()) << 32 | rng()) & ((1ull << 49) - 1);
    tb.tick();
    if (!c || !(tb->m_side & kReal)) continue;
    const auto o = t.next_out(tb->m_side);
    if (!o) break;
    const size_t opix = static_cast<size_t>(o->y) * w + o->x;
    const long lat = static_cast<long>(k - 1) - beat_of[o->frame][opix];
    if (lat != 9) {
      t.fail(fmt::format("latency at frame {} x {} y {}: {} beats, documented 9", o->frame, o->x, o->y, lat));
      continue;
    }
    const Frame& of = frames[static_cast<size_t>(o->frame)];
    const uint32_t want = pack_fields(out_fields(of.ev, o->x, o->y, hw.disp, of.regs[opix]), dw);
    t.check(tb->m_fields == want, [&] {
      return fmt::format("frame {} x {} y {}: d {} dw {} fields {:#010x}, model {:#010x}", o->frame, o->x, o->y,
                         of.ev.d.at(o->x, o->y), of.ev.dw.at(o->x, o->y), tb->m_fields, want);
    });
  }
  t.all_out();
  return t.finish(fmt::format("tb_outfields DISP={} CW={}", hw.disp, cw));
}
