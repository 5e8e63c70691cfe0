// Block test of sm_edge_flag (docs/algorithm.md section 6, "Edge-dependent penalty"):
// frames of random left pixels (smooth runs and steps, so that both sides of EDGE_T
// occur) with a random EDGE_T per frame, streamed with random ce gaps and garbage on
// idle cycles, then virtual flush rows. The flag of every beat is the model's
// (sm::edge_penalties with occ 0, occ_edge 1, on the beat's row), and after ce n the
// output must hold the flag of beat n + 2 - (ROWS * width + COLS): the beat the DP
// samples on the ce after next.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "dp.hpp"
#include "sm_block_test.hpp"

namespace {
constexpr int kMaxWidth = SM_P_MAX_WIDTH;
constexpr int kRows = SM_P_ROWS;
constexpr int kCols = SM_P_COLS;
}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_edge_flag block test"};
  sm::test::StreamShape shape{kMaxWidth};
  t.stream_options(shape, 16, kMaxWidth);
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int width = shape.width, rows = shape.rows, frames = shape.frames, idle = shape.idle;
  const uint32_t seed = shape.seed;

  std::mt19937 rng(seed);
  // Pixels of every beat of the schedule, and the frames' thresholds.
  const std::vector<int> heights(frames, rows);
  const auto sched = sm::test::make_schedule(width, heights, kRows + 2);
  std::vector<uint8_t> pix(sched.size());
  int level = 128;
  for (auto& p : pix) {
    // runs of small steps with an occasional jump: differences around every threshold
    level =
        (rng() % 8 == 0) ? static_cast<int>(rng() % 256) : std::clamp(level + static_cast<int>(rng() % 9) - 4, 0, 255);
    p = static_cast<uint8_t>(level);
  }
  std::vector<uint8_t> thr(static_cast<size_t>(frames));
  for (int f = 0; f < frames; ++f)
    thr[static_cast<size_t>(f)] = static_cast<uint8_t>(f == 0 ? 0 : f == 1 ? 255 : rng() % 24);

  // Expected flag of every beat: the model's per-row edge test with the threshold of the
  // last frame started (virtual rows after a frame keep it); beats before the first sof
  // have none (-1: not checked).
  std::vector<int> flag(sched.size(), -1);
  std::vector<uint8_t> pen;
  int cur = -1;
  for (size_t row0 = 0; row0 < sched.size(); row0 += static_cast<size_t>(width)) {
    if (sched[row0].side & sm::test::kSof) cur = sched[row0].frame;
    if (cur < 0) continue;
    sm::edge_penalties(&pix[row0], width, 0, 1, thr[static_cast<size_t>(cur)], pen);
    for (int x = 0; x < width; ++x) flag[row0 + static_cast<size_t>(x)] = pen[static_cast<size_t>(x)];
  }

  t.ce_schedule(seed * 7919u + 1, idle);
  auto& grng = t.ce_rng();
  auto& tb = t.tb();
  tb->ce = 1;
  tb->width = static_cast<uint32_t>(width);
  t.reset(4);

  const long delay = static_cast<long>(kRows) * width + kCols;
  for (size_t n = 0; n < sched.size(); ++n) {
    const auto& b = sched[n];
    while (!t.next_ce()) {  // idle cycle: everything but width random
      tb->s_side = grng() & 31;
      tb->s_left = grng() & 255;
      tb->edge_t = grng() & 255;
      tb.tick();
    }
    tb->s_side = b.side;
    tb->s_left = pix[n];
    // the frame's threshold is only guaranteed on its sof beat, where sm_edge_flag latches it
    tb->edge_t = (b.side & sm::test::kSof) ? thr[static_cast<size_t>(b.frame)] : grng() & 255;
    tb.tick();
    const long k = static_cast<long>(n) + 2 - delay;  // the beat whose flag is out now
    if (k < 0 || flag[static_cast<size_t>(k)] < 0) continue;
    const int want = flag[static_cast<size_t>(k)];
    const int got = tb->m_edge;
    t.check(got == want, [&] {
      const auto& kb = sched[static_cast<size_t>(k)];
      return fmt::format("after ce {}: beat {} (frame {} x {} y {}) flag {} want {}", n, k, kb.frame, kb.x, kb.y, got,
                         want);
    });
  }
  return t.finish(fmt::format("tb_edge_flag MAX_WIDTH={} ROWS={} COLS={} width={}", kMaxWidth, kRows, kCols, width));
}
