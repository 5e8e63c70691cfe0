// Block test of sm_dp (docs/algorithm.md, section 6): frames of aggregated-cost
// volumes (structured disparity steps, random full-range costs, tie-heavy costs) with
// a random occlusion penalty per frame, streamed with random ce gaps and garbage on
// virtual beats and idle cycles; every real output pixel is compared with trellis_dp.
// Edge-dependent penalty (s_edge, occ_edge): frame 0 has no flags (trellis_dp, as
// before); every later frame flags about a third of its pixels (column 0 never) with an
// occ_edge different from occ and is compared with trellis_line_pen (pen[x] = flag(x) ?
// occ_edge : occ, pen[W] = occ). s_edge carries the flag of the next beat; virtual rows
// get random flags except at column 0 (the flag the end node sees).
// Folded (SM_P_PU < SM_P_DISP, F = DISP/PU clocks per beat): ce at most every F clocks
// (CeGen's minimum gap) and, as sm_top guarantees, the next beat's input held from the
// clock after a ce up to its ce (no garbage on idle clocks), also for the F clocks
// after reset before the first ce.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "dp.hpp"
#include "sm_block_test.hpp"
#include "sm_port.hpp"

namespace {

constexpr int kMaxWidth = SM_P_MAX_WIDTH;
constexpr int kDisp = SM_P_DISP;
constexpr int kCw = SM_P_CW;
constexpr int kS = kDisp / 2;
constexpr int kP = 2;
#ifdef SM_P_PU
constexpr int kF = SM_P_DISP / SM_P_PU;  // clocks per beat
#else
constexpr int kF = 1;
#endif

// Pack DISP CW-bit costs, level d at bit d*CW.
std::vector<uint32_t> pack(const uint8_t* c) {
  std::vector<uint32_t> w((kDisp * kCw + 31) / 32, 0);
  for (int d = 0; d < kDisp; ++d)
    for (int b = 0; b < kCw; ++b)
      if ((c[d] >> b) & 1) w[(d * kCw + b) / 32] |= 1u << ((d * kCw + b) % 32);
  return w;
}

sm::HwConfig make_hw() {
  sm::HwConfig hw;
  hw.max_width = kMaxWidth;
  hw.disp = kDisp;
  for (int c = 3; c <= 15; c += 2)
    for (int sh = 0; sh <= 4; ++sh) {
      hw.census = c;
      hw.cost_shift = sh;
      if (hw.cost_bits() == kCw) return hw;
    }
  throw std::runtime_error(fmt::format("no CENSUS/COST_SHIFT gives CW = {}", kCw));
}

// Structured line: piecewise-constant true disparity with steps; cost grows with the
// distance from the true level, plus a little noise; x - d < 0 gets the maximum.
void structured_row(sm::CostVolume& v, int y, std::mt19937& rng) {
  const int cmax = (1 << kCw) - 1;
  int x = 0;
  while (x < v.w) {
    const int len = 3 + static_cast<int>(rng() % 12);
    const int dt = static_cast<int>(rng() % kDisp);
    for (int k = 0; k < len && x < v.w; ++k, ++x)
      for (int d = 0; d < kDisp; ++d) {
        int c = std::min(cmax, std::abs(d - dt) * 2 + static_cast<int>(rng() % 2));
        if (x - d < 0) c = cmax;
        v.at(x, y, d) = static_cast<uint8_t>(c);
      }
  }
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_dp block test"};
  int width = kMaxWidth, rows = 6, frames = 3, idle = 30;
  uint32_t seed = 1;
  t.option("--width", width, "active width");
  t.option("--rows", rows, "rows per frame");
  t.option("--frames", frames, "frames back to back");
  t.option("--seed", seed, "random seed");
  t.option("--idle", idle, "percent of cycles with ce = 0");
  if (auto rc = t.parse(argc, argv)) return *rc;
  if (width < kS + kP + 1 || width > kMaxWidth) {
    fmt::print(stderr, "tb_dp: width {} outside {}..{} (DISP/2 + 3 .. MAX_WIDTH)\n", width, kS + kP + 1, kMaxWidth);
    return 2;
  }
  if (rows < 1 || frames < 1) {
    fmt::print(stderr, "tb_dp: rows and frames must be >= 1\n");
    return 2;
  }

  const sm::HwConfig hw = make_hw();
  std::mt19937 rng(seed);
  const int cmax = (1 << kCw) - 1;
  std::vector<sm::CostVolume> vol;
  std::vector<uint8_t> occ, occ_edge;
  std::vector<std::vector<uint8_t>> flags;  // per frame, flags[f][y * width + x]
  std::vector<sm::DispImage> want;
  sm::DpScratch scratch;
  sm::DpLine line;
  for (int f = 0; f < frames; ++f) {
    sm::CostVolume v(width, rows, kDisp);
    const int kind = f % 3;
    for (int y = 0; y < rows; ++y) {
      if (kind == 0) {
        structured_row(v, y, rng);
      } else {
        const int top = kind == 1 ? cmax : 1;  // kind 2: costs 0..1, ties everywhere
        for (int x = 0; x < width; ++x)
          for (int d = 0; d < kDisp; ++d) v.at(x, y, d) = static_cast<uint8_t>(rng() % (top + 1));
      }
    }
    const uint8_t o = static_cast<uint8_t>(kind == 0 ? rng() % 48 : kind == 1 ? rng() % 256 : rng() % 3);
    vol.push_back(v);
    occ.push_back(o);
    std::vector<uint8_t> fl(static_cast<size_t>(width) * rows, 0);
    if (f == 0) {  // no flags: today's DP (occ_edge is still random, and unused)
      occ_edge.push_back(static_cast<uint8_t>(rng() & 255));
      want.push_back(sm::trellis_dp(v, o, hw));
    } else {
      // occ_edge != occ. Kinds 1 and 2: occ_edge 0..3. Against kind 1's occ (0..255, mostly
      // far above the costs) the path changes level almost only at flagged pixels, and
      // cheaply enough to reach the high levels (a flag one beat or one group off shows
      // there); kind 2 (costs 0..1, occ 0..2) is ties. Kind 0 in the range of its occ.
      const unsigned range = kind == 0 ? 48 : 4;
      uint8_t oe = static_cast<uint8_t>(rng() % range);
      if (oe == o) oe = static_cast<uint8_t>((o + 1) % range);
      occ_edge.push_back(oe);
      sm::DispImage img(width, rows);
      std::vector<uint8_t> pen(static_cast<size_t>(width) + 1);
      for (int y = 0; y < rows; ++y) {
        for (int x = 0; x < width; ++x) {
          const bool e = x > 0 && rng() % 3 == 0;
          fl[static_cast<size_t>(y) * width + x] = e;
          pen[x] = e ? oe : o;
        }
        pen[width] = o;  // column 0 of the next row, flag 0
        sm::trellis_line_pen(v.pix(0, y), width, pen.data(), hw, scratch, line);
        std::copy(line.disp.begin(), line.disp.end(), &img.at(0, y));
      }
      want.push_back(img);
    }
    flags.push_back(fl);
  }

  const std::vector<int> heights(frames, rows);
  const auto sched = sm::test::make_schedule(width, heights, 3);
  t.expect_frames(width, heights);
  t.ce_schedule(seed * 7919u + 1, idle, kF);
  auto& grng = t.ce_rng();
  auto& tb = t.tb();
  std::vector<uint8_t> garbage(kDisp);
  auto random_cost = [&]() {
    for (auto& g : garbage) g = static_cast<uint8_t>(grng() % (cmax + 1));
    return pack(garbage.data());
  };
  tb->ce = 1;
  tb->width = width;
  tb->s_side = 0;
  tb->occ = 0;
  tb->occ_edge = 0;
  tb->s_edge = 0;
  t.reset(4);

  // Edge flag of every beat: the frame's flags; virtual rows random, column 0 always 0.
  std::vector<uint8_t> beat_flag(sched.size());
  for (size_t i = 0; i < sched.size(); ++i) {
    const auto& b = sched[i];
    if (b.frame >= 0)
      beat_flag[i] = flags[b.frame][static_cast<size_t>(b.y) * width + b.x];
    else
      beat_flag[i] = b.x > 0 && grng() % 2 == 0;
  }

  // The input of one beat, fixed when the beat is first driven (held at F > 1).
  struct Drive {
    uint8_t side = 0, occ = 0, occ_edge = 0, edge = 0;
    std::vector<uint32_t> cost;
  };
  auto beat_input = [&](size_t bi) {
    const sm::test::BeatInfo& b = sched[bi];
    Drive d;
    d.side = b.side;
    d.edge = bi + 1 < sched.size() ? beat_flag[bi + 1] : 0;  // s_edge: the next beat's flag
    if (b.frame >= 0) {
      d.cost = pack(vol[b.frame].pix(b.x, b.y));
      // the frame's penalties are only guaranteed where sm_dp latches them
      const bool latch = b.y == 0 && b.x < kS;
      d.occ = latch ? occ[b.frame] : static_cast<uint8_t>(grng() & 255);
      d.occ_edge = latch ? occ_edge[b.frame] : static_cast<uint8_t>(grng() & 255);
    } else {
      d.cost = random_cost();
      d.occ = static_cast<uint8_t>(grng() & 255);
      d.occ_edge = static_cast<uint8_t>(grng() & 255);
    }
    return d;
  };
  auto drive = [&](const Drive& d) {
    tb->s_side = d.side;
    tb->occ = d.occ;
    tb->occ_edge = d.occ_edge;
    tb->s_edge = d.edge;
    sm::test::set_port_words(tb->s_cost, d.cost, kDisp * kCw);
  };
  Drive first;                     // F > 1: beat 0's input, driven from reset on
  if (kF > 1 && !sched.empty()) {  // the first beat's sub-steps run on the F clocks after reset
    first = beat_input(0);
    tb->ce = 0;
    drive(first);
    for (int i = 0; i < kF; ++i) tb.tick();
  }

  bool order_error = false;
  for (size_t bi = 0; bi < sched.size(); ++bi) {
    const Drive in = (kF > 1 && bi == 0) ? first : beat_input(bi);
    for (;;) {
      if (!t.next_ce()) {
        if (kF > 1) {  // folded: the beat is held until its ce
          drive(in);
        } else {  // idle cycle: everything random
          tb->s_side = grng() & 31;
          tb->occ = grng() & 255;
          tb->occ_edge = grng() & 255;
          tb->s_edge = grng() & 1;
          sm::test::set_port_words(tb->s_cost, random_cost(), kDisp * kCw);
        }
        tb.tick();
        continue;
      }
      drive(in);
      tb.tick();
      const uint8_t side = tb->m_side;
      if ((side & sm::test::kReal) && !order_error) {
        const auto o = t.next_out(side);
        if (!o) {  // the rest of the stream is driven, not compared
          order_error = true;
          break;
        }
        const unsigned exp = want[o->frame].at(o->x, o->y);
        const unsigned got = tb->m_disp;
        t.check(exp == got, [&] {
          return fmt::format("frame {} x {} y {} expected 0x{:04x} got 0x{:04x}", o->frame, o->x, o->y, exp, got);
        });
      }
      break;
    }
  }
  t.all_out();
  return t.finish(fmt::format("tb_dp MAX_WIDTH={} DISP={} CW={} F={} width={}", kMaxWidth, kDisp, kCw, kF, width));
}
