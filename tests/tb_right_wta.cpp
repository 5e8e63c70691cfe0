// Block test of sm_right_wta (docs/algorithm.md section 9.0, field lr): frames of
// aggregated-cost lines streamed with random ce gaps and garbage on virtual beats and
// idle cycles; every real output beat's level is compared with the model's right_wta of
// its line, and the model with the definition computed here (the lowest k of least
// A(xr + k, k) over xr + k < W). Rows are tie-heavy by turns: full-range random costs,
// a narrow range (two or three values), one constant for the whole row, one constant per
// pixel, and a cost valley |k - t| / 2 around a random level (ties in pairs). Widths
// below DISP - 1 included: the block needs none, ceil((DISP - 1) / W) + 1 virtual rows
// flush the stream.
// Folded (SM_P_PU < SM_P_DISP, F = DISP/PU clocks per beat): ce at most every F clocks
// (CeGen's minimum gap) and, as sm_top guarantees, the next beat's input held from the
// clock after a ce up to its ce (no garbage on idle clocks), also for the F clocks after
// reset before the first ce.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "evidence.hpp"
#include "sm_block_test.hpp"
#include "held_beats.hpp"
#include "sm_port.hpp"

namespace {

constexpr int kMaxWidth = SM_P_MAX_WIDTH;
constexpr int kDisp = SM_P_DISP;
constexpr int kCw = SM_P_CW;
constexpr int kCmax = (1 << kCw) - 1;
#ifdef SM_P_PU
constexpr int kF = SM_P_DISP / SM_P_PU;  // clocks per beat
#else
constexpr int kF = 1;
#endif

// Pack DISP CW-bit costs, level k at bit k*CW.
std::vector<uint32_t> pack(const uint8_t* c) { return sm::test::pack_values(c, kDisp, kCw); }

// One line of costs, agg[x * DISP + k], of the given kind (0..4, see the file comment).
void make_line(uint8_t* agg, int w, int kind, std::mt19937& rng) {
  const int lo = static_cast<int>(rng() % (kCmax + 1));
  const int span = 1 + static_cast<int>(rng() % 3);  // kind 1: lo .. lo + span - 1 (clamped)
  for (int x = 0; x < w; ++x) {
    const int pix = static_cast<int>(rng() % (kCmax + 1));
    const int t = static_cast<int>(rng() % kDisp);
    for (int k = 0; k < kDisp; ++k) {
      int c = 0;
      switch (kind) {
        case 0:
          c = static_cast<int>(rng() % (kCmax + 1));
          break;
        case 1:
          c = std::min(kCmax, lo + static_cast<int>(rng() % span));
          break;
        case 2:
          c = lo;
          break;
        case 3:
          c = pix;
          break;
        default:
          c = std::min(kCmax, std::abs(k - t) / 2);
          break;
      }
      agg[static_cast<size_t>(x) * kDisp + k] = static_cast<uint8_t>(c);
    }
  }
}

// The definition: the lowest k of least A(xr + k, k) over k < DISP with xr + k < w.
std::vector<uint8_t> right_wta_def(const uint8_t* agg, int w) {
  std::vector<uint8_t> out(static_cast<size_t>(w));
  for (int xr = 0; xr < w; ++xr) {
    int best = 0;
    for (int k = 1; k < kDisp && xr + k < w; ++k)
      if (agg[static_cast<size_t>(xr + k) * kDisp + k] < agg[static_cast<size_t>(xr + best) * kDisp + best]) best = k;
    out[static_cast<size_t>(xr)] = static_cast<uint8_t>(best);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_right_wta block test"};
  sm::test::StreamShape shape{kMaxWidth};
  t.stream_options(shape, 1, kMaxWidth);
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int width = shape.width, rows = shape.rows, frames = shape.frames, idle = shape.idle;
  const uint32_t seed = shape.seed;

  // Costs (vol[f][(y * width + x) * DISP + k]) and the expected levels (want[f][y * width + x]).
  std::mt19937 rng(seed);
  const size_t line_n = static_cast<size_t>(width) * kDisp;
  std::vector<std::vector<uint8_t>> vol, want;
  std::vector<uint8_t> lr;
  for (int f = 0; f < frames; ++f) {
    std::vector<uint8_t> v(line_n * rows);
    std::vector<uint8_t> wf;
    for (int y = 0; y < rows; ++y) {
      const uint8_t* agg = &v[line_n * y];
      make_line(&v[line_n * y], width, static_cast<int>((f * rows + y + rng() % 2) % 5), rng);
      sm::right_wta(agg, width, kDisp, lr);
      const std::vector<uint8_t> def = right_wta_def(agg, width);
      t.check(lr == def,
              [&] { return fmt::format("model right_wta differs from the definition, frame {} y {}", f, y); });
      wf.insert(wf.end(), lr.begin(), lr.end());
    }
    vol.push_back(std::move(v));
    want.push_back(std::move(wf));
  }

  // Enough virtual rows to push the last line's DISP - 1 beats of latency out.
  const int flush = (kDisp - 1 + width - 1) / width + 1;
  const std::vector<int> heights(frames, rows);
  const auto sched = sm::test::make_schedule(width, heights, flush);
  t.expect_frames(width, heights);
  t.ce_schedule(seed * 7919u + 1, idle, kF);
  auto& grng = t.ce_rng();
  auto& tb = t.tb();
  std::vector<uint8_t> garbage(kDisp);
  auto random_cost = [&]() {
    for (auto& g : garbage) g = static_cast<uint8_t>(grng() % (kCmax + 1));
    return pack(garbage.data());
  };
  tb->ce = 1;
  tb->width = static_cast<uint32_t>(width);
  tb->s_side = 0;
  t.reset(4);

  // The input of one beat, fixed when the beat is first driven (held at F > 1).
  struct Drive {
    uint8_t side = 0;
    std::vector<uint32_t> cost;
  };
  auto beat_input = [&](size_t bi) {
    const sm::test::BeatInfo& b = sched[bi];
    Drive d;
    d.side = b.side;
    d.cost = b.frame >= 0 ? pack(&vol[b.frame][(static_cast<size_t>(b.y) * width + b.x) * kDisp]) : random_cost();
    return d;
  };
  auto drive = [&](const Drive& d) {
    tb->s_side = d.side;
    sm::test::set_port_words(tb->s_cost, d.cost, kDisp * kCw);
  };
  auto idle_inputs = [&] {
    tb->s_side = grng() & 31;
    sm::test::set_port_words(tb->s_cost, random_cost(), kDisp * kCw);
  };
  auto compare = [&](size_t) {
    const uint8_t side = tb->m_side;
    if (!(side & sm::test::kReal)) return true;
    const auto o = t.next_out(side);
    if (!o) return false;  // out of order: the rest cannot be compared
    const unsigned exp = want[o->frame][static_cast<size_t>(o->y) * width + o->x];
    const unsigned got = tb->m_lr;
    t.check(exp == got, [&] {
      return fmt::format("frame {} xr {} y {} expected level {} got {}", o->frame, o->x, o->y, exp, got);
    });
    return true;
  };
  sm::test::run_held_beats(
      t, sched.size(), kF, beat_input, drive, idle_inputs, [](size_t) {}, compare);
  t.all_out();
  return t.finish(
      fmt::format("tb_right_wta MAX_WIDTH={} DISP={} CW={} F={} width={}", kMaxWidth, kDisp, kCw, kF, width));
}
