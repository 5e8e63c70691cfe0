// Stream of independent input vectors through a fixed-latency per-beat block (one result
// per ce, `latency` ce's after its inputs; the sideband s_side -> m_side delayed beside
// it by sm_side_delay), for the arithmetic blocks' exhaustive tests (tb_subpix_fit,
// tb_conf_ratio). Random ce gaps with random garbage on the inputs of every idle clock;
// every beat carries a random sideband. Checked: m_side is 0 from reset until the first
// beat arrives, each output beat's sideband is its input beat's, the outputs do not move
// on clocks without ce, and `check(v, got)` compares each vector's result.
#pragma once

#include <cstdint>
#include <deque>
#include <random>
#include <utility>
#include <vector>

#include "sm_block_test.hpp"
#include "sm_defs.hpp"

namespace sm::test {

// gen(rng) -> a random Vec (garbage and the flush beats after the list, which are checked
// too); drive(top, v) sets the data inputs; out(top) -> the data outputs as one word.
template <class Top, class Vec, class Gen, class Drive, class Out, class Check>
void stream_vectors(BlockTest<Top>& t, const std::vector<Vec>& vecs, int latency, uint32_t seed, int idle_percent,
                    Gen&& gen, Drive&& drive, Out&& out, Check&& check) {
  constexpr uint32_t kSideMask = (1u << defs::kSideW) - 1;
  t.ce_schedule(seed, idle_percent);
  auto& rng = t.ce_rng();
  Top& top = t.tb().top();
  t.reset(4, [&] {  // garbage and random ce during reset
    top.ce = rng() & 1;
    top.s_side = rng() & kSideMask;
    drive(top, gen(rng));
  });
  struct Beat {
    Vec v;
    uint8_t side;
  };
  std::deque<Beat> pipe;  // beats in flight, oldest first
  size_t next = 0, done = 0;
  uint8_t last_side = top.m_side;
  uint32_t last_out = out(top);
  while (done < vecs.size()) {
    const bool ce = t.next_ce();
    Beat b{next < vecs.size() ? vecs[next] : gen(rng), static_cast<uint8_t>(rng() & kSideMask)};
    if (!ce) b.v = gen(rng);  // garbage: must not be sampled
    top.s_side = b.side;
    drive(top, b.v);
    t.tick();
    const uint8_t side = top.m_side;
    const uint32_t got = out(top);
    if (!ce) {
      t.check(side == last_side && got == last_out, [&] {
        return fmt::format("outputs moved without ce: side {:#x} -> {:#x}, data {:#x} -> {:#x}", last_side, side,
                           last_out, got);
      });
      continue;
    }
    last_side = side;
    last_out = got;
    if (next < vecs.size()) ++next;
    pipe.push_back(b);
    if (static_cast<int>(pipe.size()) < latency) {  // the reset sideband still leaving
      t.check(side == 0, [&] { return fmt::format("m_side {:#x} before the first beat arrived, want 0", side); });
      continue;
    }
    const Beat o = pipe.front();
    pipe.pop_front();
    t.check(side == o.side, [&] { return fmt::format("m_side {:#x}, want the beat's {:#x}", side, o.side); });
    check(o.v, got);
    if (done < vecs.size()) ++done;
  }
}

}  // namespace sm::test
