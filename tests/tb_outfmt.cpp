// Block test of sm_outfmt: the beat schedule (frames of W-beat rows + virtual rows,
// random garbage on virtual beats and ce=0 cycles) is fed at ce = have_beat && room
// with random ce gaps, the sink applies random back-pressure. Every real beat must come
// out once, in order, with its data, tuser on the frame's first pixel and tlast at
// x == W-1 (two widths, frames back to back); room must prevent any loss. A final phase
// ignores room on purpose and checks that exactly the beats beyond the FIFO's capacity
// are reported as overflow. Soft-reset phases last: the frame the sink is receiving is
// completed (queued pixels, then 0 words), everything else queued is dropped.
#include <algorithm>
#include <cstdint>
#include <deque>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include SM_VTOP_H
#include "sm_block_test.hpp"

using sm::test::BeatInfo;

namespace {

struct Expect {
  int frame, x, y;
  uint32_t data;
  bool user, last;
};

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_outfmt block test"};
  bool paper = false;
  t.flag("--paper", paper, "the paper point's widths and heights (320 and 200 wide)");
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int W1 = paper ? 320 : 37, W2 = paper ? 200 : 21;
  const std::vector<int> h1 = paper ? std::vector<int>{3, 2} : std::vector<int>{5, 4};
  const std::vector<int> h2 = paper ? std::vector<int>{2} : std::vector<int>{3, 6};
  constexpr int kCap = SM_P_FIFO_DEPTH + 1;

  // Schedule: width W1 frames, then width W2 frames (widths differ per beat).
  struct Slot {
    BeatInfo b;
    int w;
  };
  std::vector<Slot> sched;
  for (const auto& b : sm::test::make_schedule(W1, h1, 2, 1)) sched.push_back({b, W1});
  for (auto b : sm::test::make_schedule(W2, h2, 3, 0)) {
    if (b.frame >= 0) b.frame += static_cast<int>(h1.size());
    b.side = static_cast<uint8_t>((b.side & 7) | (((b.frame >= 0 ? b.frame : 3) & 3) << 3));
    sched.push_back({b, W2});
  }

  std::mt19937 rng(99);
  std::vector<std::vector<uint32_t>> img;  // disparity words by frame
  std::deque<Expect> expect;
  for (const auto& s : sched) {
    if (s.b.frame < 0) continue;
    if (static_cast<int>(img.size()) <= s.b.frame) img.resize(static_cast<size_t>(s.b.frame) + 1);
    const uint32_t d = static_cast<uint32_t>(rng());  // any word: the formatter passes it through
    img[static_cast<size_t>(s.b.frame)].push_back(d);
    expect.push_back({s.b.frame, s.b.x, s.b.y, d, s.b.x == 0 && s.b.y == 0, s.b.x == s.w - 1});
  }
  const size_t total = expect.size();

  auto* top = &t.tb().top();
  auto tick = [&] { t.tick(); };
  top->ce = 0;
  top->m_axis_tready = 0;
  top->width = W1;
  t.reset(4);

  // not next_ce(): ce also waits for room
  sm::test::CeGen ce_gen(5, 30);
  size_t next = 0, got = 0;
  int overflows = 0;
  uint64_t cycles = 0;
  const int bp = 45;  // percent of cycles with tready low
  while ((next < sched.size() || got < total) && cycles < 2000000) {
    ++cycles;
    const bool have = next < sched.size();
    const bool ce = have && ce_gen.next() && top->room;
    top->ce = ce;
    if (ce) {
      const auto& s = sched[next].b;
      top->in_side = s.side;
      top->width = sched[next].w;
      if (s.frame >= 0)
        top->height =
            static_cast<uint32_t>(s.frame < static_cast<int>(h1.size()) ? h1[static_cast<size_t>(s.frame)]
                                                                        : h2[static_cast<size_t>(s.frame) - h1.size()]);
      top->in_word = s.frame >= 0 ? img[static_cast<size_t>(s.frame)][static_cast<size_t>(s.y * sched[next].w + s.x)]
                                  : static_cast<uint32_t>(rng());
    } else {                                              // garbage
      top->in_side = static_cast<uint8_t>(rng() & 0x1e);  // never real: not taken anyway
      top->in_word = static_cast<uint32_t>(rng());
      if (rng() & 1) top->in_side = static_cast<uint8_t>(rng() & 0x1f);
    }
    top->m_axis_tready = static_cast<int>(rng() % 100) >= bp;
    top->eval();
    if (top->m_axis_tvalid && top->m_axis_tready) {
      if (t.check(got < total, "more output beats than real input beats")) {
        const Expect& e = expect[got];
        t.check(top->m_axis_tdata == e.data && top->m_axis_tuser == e.user && top->m_axis_tlast == e.last,
                fmt::format("frame {} x {} y {}: expected data 0x{:04x} user {} last {}, got 0x{:04x} {} {}", e.frame,
                            e.x, e.y, e.data, e.user, e.last, top->m_axis_tdata, top->m_axis_tuser, top->m_axis_tlast));
      }
      ++got;
    }
    if (top->err_overflow) ++overflows;
    tick();
    if (ce) ++next;
  }
  t.check(got == total, fmt::format("{} of {} real beats came out", got, total));
  t.check(overflows == 0, fmt::format("{} overflow pulses with room respected", overflows));

  // Overflow phase: sink stopped, real beats pushed regardless of room.
  top->m_axis_tready = 0;
  overflows = 0;
  const int pushed = kCap + 5;
  for (int i = 0; i < pushed; ++i) {
    top->ce = 1;
    top->in_side = static_cast<uint8_t>(sm::test::kReal | (i % W1 == 0 ? sm::test::kSol : 0));
    top->in_word = static_cast<uint32_t>(i);
    top->eval();
    if (top->err_overflow) ++overflows;
    tick();
  }
  top->ce = 0;
  for (int i = 0; i < 3; ++i) {
    top->eval();
    if (top->err_overflow) ++overflows;
    t.check(!top->room, "room while the FIFO is full");
    tick();
  }
  t.check(overflows == pushed - kCap, fmt::format("overflow pulses {} expected {}", overflows, pushed - kCap));
  int drained = 0;
  top->m_axis_tready = 1;
  for (int i = 0; i < 3 * kCap; ++i) {
    top->eval();
    if (top->m_axis_tvalid) {
      t.check(top->m_axis_tdata == static_cast<uint32_t>(drained),
              fmt::format("overflow phase: word {} is {}", drained, top->m_axis_tdata));
      ++drained;
    }
    tick();
  }
  t.check(drained == kCap, fmt::format("drained {} words, capacity {}", drained, kCap));
  top->eval();
  t.check(top->room, "room after draining");

  // Soft-reset phases (restart = the pipeline's reset, the output's own reset stays
  // high): the frame the sink is receiving is completed -- queued pixels, then 0 words --
  // every other queued beat is dropped, and room stays low until the FIFO is empty.
  struct Out {
    uint32_t d;
    bool u, l;
  };
  std::vector<Out> seen;
  auto step = [&](bool ce, uint8_t side, uint32_t d, bool ready, bool restart) {
    top->ce = ce;
    top->in_side = side;
    top->in_word = d;
    top->m_axis_tready = ready;
    top->restart = restart;
    top->eval();
    if (top->m_axis_tvalid && top->m_axis_tready)
      seen.push_back({top->m_axis_tdata, top->m_axis_tuser != 0, top->m_axis_tlast != 0});
    tick();
  };
  // frame of the soft-reset phases: R2 queues it whole plus part of the next one
  const int RW = kCap > 64 ? 19 : 3, RH = kCap > 64 ? 5 : 2, NXT = std::min(7, kCap - RW * RH - 1);
  top->width = RW;
  top->height = RH;
  auto write_px = [&](int i, uint32_t d, bool ready) {  // pixel i of an RW x RH frame
    const uint8_t side =
        static_cast<uint8_t>(sm::test::kReal | (i == 0 ? sm::test::kSof : 0) | (i % RW == 0 ? sm::test::kSol : 0));
    for (int guard = 0; !top->room; ++guard) {
      if (!t.check(guard < 10 * kCap + 10 * RW * RH, "room comes back (soft-reset phases)"))
        throw std::runtime_error("no room");
      step(false, 0, 0, ready, false);
    }
    step(true, side, d, ready, false);
  };
  auto settle = [&](int n, bool ready) {
    for (int i = 0; i < n; ++i) step(false, 0, 0, ready, false);
  };
  auto expect_frame = [&](const std::vector<uint32_t>& want, const std::string& what) {
    bool ok = seen.size() == want.size();
    for (size_t i = 0; ok && i < want.size(); ++i)
      ok = seen[i].d == want[i] && seen[i].u == (i == 0) && seen[i].l == (static_cast<int>(i) % RW == RW - 1);
    t.check(ok, fmt::format("{}: {} beats out, expected {}", what, seen.size(), want.size()));
    seen.clear();
  };
  auto pixels = [&](int n, uint32_t base) {
    std::vector<uint32_t> v;
    for (int i = 0; i < n; ++i) v.push_back(static_cast<uint32_t>(base + i));
    return v;
  };
  settle(3 * kCap, true);
  seen.clear();
  try {
    // R1: the sink is inside a frame the pipeline had delivered a row and a pixel of.
    {
      const int k = RW + 1;
      for (int i = 0; i < k; ++i) write_px(i, static_cast<uint32_t>(0x8100 + i), true);
      settle(10, true);
      step(false, 0, 0, true, true);
      for (int i = 0; i < 3 * RW * RH; ++i) {
        step(false, 0, 0, true, false);
        if (top->room && i > RW * RH) break;
      }
      std::vector<uint32_t> want = pixels(k, 0x8100);
      want.resize(RW * RH, 0);
      expect_frame(want, "soft reset inside the sink's frame: padded to W x H");
      t.check(top->room, "room after the padded frame");
    }
    // R2: the sink holds the first frame's tuser beat; the FIFO holds the rest of it and
    // part of the next frame, which is dropped.
    {
      for (int i = 0; i < RW * RH; ++i) write_px(i, static_cast<uint32_t>(0x8200 + (i & 0xff)), false);
      for (int i = 0; i < NXT; ++i) write_px(i, static_cast<uint32_t>(0x8300 + i), false);
      settle(5, false);
      t.check(top->m_axis_tvalid && top->m_axis_tuser, "the first frame's tuser beat is offered");
      step(false, 0, 0, false, true);
      settle(20, false);
      t.check(!top->room, "no room while the flush waits for the sink");
      int guard = 0;
      while (!top->room && ++guard < 1000) step(false, 0, 0, true, false);
      std::vector<uint32_t> want;
      for (int i = 0; i < RW * RH; ++i) want.push_back(static_cast<uint32_t>(0x8200 + (i & 0xff)));
      expect_frame(want, "soft reset with the sink's frame queued whole: delivered, the next frame dropped");
      settle(20, true);
      t.check(seen.empty(), "nothing after the dropped frame");
    }
    // R3: no frame on the wire (a beat written but not yet at the FIFO head): dropped.
    {
      write_px(0, 0x8400, true);
      step(false, 0, 0, true, true);
      settle(30, true);
      t.check(seen.empty(), "a frame not yet offered is dropped by a soft reset");
    }
    // After all three, a frame passes intact.
    {
      for (int i = 0; i < RW * RH; ++i) write_px(i, static_cast<uint32_t>(0x8500 + i), true);
      settle(30, true);
      expect_frame(pixels(RW * RH, 0x8500), "first frame after the soft resets");
    }
  } catch (const std::runtime_error&) {
    // reported by t.check()
  }

  return t.finish(fmt::format("tb_outfmt FIFO_DEPTH={}", SM_P_FIFO_DEPTH));
}
