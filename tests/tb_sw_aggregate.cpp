// Block test of sm_sw_aggregate against the model sw_aggregate (docs/algorithm.md,
// section 5): frames of random raw costs and partly smooth, partly noisy left images,
// a different weight table per frame (checks the latch at the stage's sof), random ce
// gaps, garbage on virtual beats and idle cycles. Every real output pixel is compared
// bit for bit, and its beat must leave exactly at the documented latency. Folded
// (SM_P_PU < SM_P_DISP, F = DISP / PU clocks per beat): ce is low on the F - 1 clocks
// after every high one (sm_top's pacing) and the next beat's input is held from the
// clock after a ce up to its own ce, as the previous stage's output register would be.
// The port takes C = raw >> COST_SHIFT (sm_cost's output), the model the raw costs.
// --max-cost-frame appends a frame whose raw costs all sit at 2^HW - 1 (C at the port's
// maximum 2^CW - 1): the widest weighted terms and sums, and -- where the cost width allows it --
// windows whose normalised cost rounds above 2^CW - 1 and must saturate (sm_sw_level).
#include SM_VTOP_H

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "aggregate.hpp"
#include "sm_block_test.hpp"
#include "sm_port.hpp"

namespace {

constexpr int kMaxWidth = SM_P_MAX_WIDTH;
constexpr int kDisp = SM_P_DISP;
constexpr int kCensus = SM_P_CENSUS;
constexpr int kSw = SM_P_SW;
constexpr int kCostShift = SM_P_COST_SHIFT;
constexpr int kR = (kSw - 1) / 2;
#ifdef SM_P_PU
constexpr int kFold = SM_P_DISP / SM_P_PU;  // clocks per beat
#else
constexpr int kFold = 1;
#endif
constexpr int kPipe = sm::defs::kAggPipeBeats;  // beats from the window's entering beat to the output, inclusive

// A bit vector of the given width as 32-bit words (bit b at word b / 32), as
// sm::test::set_port_words / get_port_words take them.
using Bits = std::vector<uint32_t>;
Bits make_bits(int width) { return Bits(static_cast<size_t>((width + 31) / 32), 0u); }
void put_field(Bits& b, int lsb, int n, uint32_t v) {
  for (int i = 0; i < n; ++i) {
    const int bit = lsb + i;
    const uint32_t m = 1u << (bit & 31);
    if ((v >> i) & 1u)
      b[static_cast<size_t>(bit >> 5)] |= m;
    else
      b[static_cast<size_t>(bit >> 5)] &= ~m;
  }
}
uint32_t get_field(const Bits& b, int lsb, int n) {
  uint32_t v = 0;
  for (int i = 0; i < n; ++i) {
    const int bit = lsb + i;
    v |= ((b[static_cast<size_t>(bit >> 5)] >> (bit & 31)) & 1u) << i;
  }
  return v;
}
void random_bits(Bits& b, int width, std::mt19937& rng) {
  for (auto& w : b) w = rng();
  if (width % 32) b.back() &= (1u << (width % 32)) - 1u;
}

struct Frame {
  sm::Image8 left;
  sm::CostVolume raw;
  std::array<uint8_t, 32> table{};
  sm::CostVolume expect;
};

// Left image: blocks of smooth gradient with small noise beside blocks of full-range
// noise, so every |dI| >> 3 bucket (hence every weight code) occurs.
sm::Image8 make_left(int w, int h, std::mt19937& rng) {
  sm::Image8 im(w, h);
  std::uniform_int_distribution<int> noise(0, 255), small(-3, 3), base(20, 200);
  const int b0 = base(rng);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool smooth = ((x / 8) + (y / 4)) % 3 != 0;
      const int v = smooth ? b0 + 2 * x + y + small(rng) : noise(rng);
      im.at(x, y) = static_cast<uint8_t>(std::clamp(v, 0, 255));
    }
  return im;
}

std::array<uint8_t, 32> make_table(std::mt19937& rng) {
  std::array<uint8_t, 32> t{};
  for (auto& c : t) c = static_cast<uint8_t>(rng() & 3);
  // All four codes surely occur, on the small differences that smooth regions produce.
  t[0] = 3;
  t[1] = 2;
  t[2] = 1;
  t[3] = 0;
  return t;
}

uint64_t pack_table(const std::array<uint8_t, 32>& t) {
  uint64_t v = 0;
  for (int k = 0; k < 32; ++k) v |= static_cast<uint64_t>(t[static_cast<size_t>(k)] & 3) << (2 * k);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_sw_aggregate block test"};
  int width = 37;
  std::vector<int> heights{9, 6, 11};
  uint32_t seed = 1;
  int idle = 30;
  bool max_cost_frame = false;
  t.option("--width", width, "active width").range(kSw, kMaxWidth);
  t.option("--heights", heights, "rows of each frame, sent back to back");
  t.option("--seed", seed, "random seed");
  t.option("--idle", idle, "percent of cycles with ce low").range(0, 95);
  t.flag("--max-cost-frame", max_cost_frame,
         "append a frame with every raw cost at the port's maximum (saturation, widest sums)");
  if (auto rc = t.parse(argc, argv)) return *rc;
  if (max_cost_frame) heights.push_back(heights.empty() ? kR + 1 : heights.back());

  // Each frame's table is put on sw_table when its first beat enters (as the shadow
  // registers would be); the stage latches it R rows + R columns later, so the next frame
  // may start no earlier than that: at least R + 1 rows per frame (the core's minimum
  // height is 16).
  for (int h : heights)
    if (h < kR + 1) {
      fmt::print("error: --heights {} is below R + 1 = {} rows\n", h, kR + 1);
      return 2;
    }

  sm::HwConfig hw;
  hw.max_width = kMaxWidth;
  hw.disp = kDisp;
  hw.census = kCensus;
  hw.sw = kSw;
  hw.cost_shift = kCostShift;
  const int cb = hw.census_bits();
  const int hwid = sm::clog2(cb + 1);
  const int cw = hw.cost_bits();

  std::mt19937 rng(seed);
  std::vector<Frame> frames;
  for (size_t i = 0; i < heights.size(); ++i) {
    const int h = heights[i];
    const bool at_max = max_cost_frame && i + 1 == heights.size();
    Frame f;
    f.left = make_left(width, h, rng);
    f.raw = sm::CostVolume(width, h, kDisp);
    std::uniform_int_distribution<int> cost(0, cb);
    for (auto& v : f.raw.v) v = static_cast<uint8_t>(at_max ? (1 << hwid) - 1 : cost(rng));
    f.table = make_table(rng);
    if (at_max) {
      // Apart from the model's aggregation (only its weight and RECIP definitions): an
      // inside window of costs all at cm = (2^HW - 1) >> COST_SHIFT has A_raw = cm * wsum,
      // so it saturates exactly when (cm * wsum * RECIP(wsum) + 2048) >> 12 > 2^CW - 1.
      // Count such windows, and require one wherever some weight sum can do it, so the
      // saturation is exercised.
      const uint32_t cm = ((1u << hwid) - 1u) >> kCostShift, omax = (1u << cw) - 1u;
      auto saturates = [&](uint32_t s) { return ((cm * s * sm::sw_recip(s) + 2048u) >> 12) > omax; };
      bool possible = false;
      for (uint32_t s = 1; s <= 4u * kSw * kSw; ++s) possible = possible || saturates(s);
      long windows = 0;
      for (int y = kR; y + kR < h; ++y)
        for (int x = kR; x + kR < width; ++x) {
          uint32_t s = 0;
          for (int j = -kR; j <= kR; ++j)
            for (int k = -kR; k <= kR; ++k)
              s += sm::sw_weight(f.table, std::abs(f.left.at(x + k, y + j) - f.left.at(x, y)));
          windows += saturates(s);
        }
      fmt::print("max-cost frame: {} inside windows saturate (possible at this point: {})\n", windows, possible);
      t.check(!possible || windows > 0, "the max-cost frame has no saturating window: choose another --seed");
    }
    f.expect = sm::sw_aggregate(f.raw, f.left, f.table, hw);
    frames.push_back(std::move(f));
  }
  const auto sched = sm::test::make_schedule(width, heights, kR + 2);
  std::vector<size_t> frame_start(frames.size(), 0);
  for (size_t i = 0; i < sched.size(); ++i)
    if (sched[i].frame >= 0 && sched[i].x == 0 && sched[i].y == 0) frame_start[static_cast<size_t>(sched[i].frame)] = i;

  auto& tb = t.tb();
  t.ce_schedule(seed * 7919u + 1u, idle, kFold);
  std::mt19937& grng = t.ce_rng();
  const int cost_bits = kDisp * cw, agg_bits = kDisp * cw;
  Bits cost_in = make_bits(cost_bits);

  auto garbage = [&]() {
    random_bits(cost_in, cost_bits, grng);
    sm::test::set_port_words(tb->s_cost, cost_in, cost_bits);
    tb->s_left = static_cast<uint8_t>(grng());
    tb->s_side = static_cast<uint8_t>(grng() & 31);
    tb->sw_table = (static_cast<uint64_t>(grng()) << 32) | grng();
  };

  tb->width = static_cast<uint32_t>(width);
  tb->ce = 1;
  t.reset(3, garbage);

  t.expect_frames(width, heights);
  uint64_t table_now = pack_table(frames[0].table);  // the shadow register's value
  // The inputs of beat t (random costs and pixel on virtual beats).
  auto drive = [&](size_t n) {
    const auto& b = sched[n];
    tb->s_side = b.side;
    if (b.frame >= 0) {
      const Frame& f = frames[static_cast<size_t>(b.frame)];
      if (b.x == 0 && b.y == 0) table_now = pack_table(f.table);
      // bit-plane order: bit i of level d at i*DISP + d
      for (int d = 0; d < kDisp; ++d)
        for (int i = 0; i < cw; ++i)
          put_field(cost_in, i * kDisp + d, 1, (f.raw.at(b.x, b.y, d) >> (kCostShift + i)) & 1u);
      sm::test::set_port_words(tb->s_cost, cost_in, cost_bits);
      tb->s_left = f.left.at(b.x, b.y);
    } else {
      random_bits(cost_in, cost_bits, grng);
      sm::test::set_port_words(tb->s_cost, cost_in, cost_bits);
      tb->s_left = static_cast<uint8_t>(grng());
    }
    tb->sw_table = table_now;
  };
  for (size_t n = 0; n < sched.size(); ++n) {
    if (kFold > 1) {
      // held from the clock after the previous ce up to this beat's ce
      drive(n);
      while (!t.next_ce()) tb.tick();
    } else {
      while (!t.next_ce()) {
        garbage();
        tb.tick();
      }
      drive(n);
    }
    tb.tick();

    const uint8_t side = tb->m_side;
    if (!(side & sm::test::kReal)) continue;
    const auto o = t.next_out(side);
    if (!o) break;
    const size_t want_n = frame_start[static_cast<size_t>(o->frame)] + static_cast<size_t>(o->y) * width + o->x +
                          static_cast<size_t>(kR) * width + kR + (kPipe - 1);
    if (n != want_n) {
      t.fail(
          fmt::format("pixel (frame {}, x {}, y {}) left after beat {}, expected {}", o->frame, o->x, o->y, n, want_n));
      break;
    }
    const Bits got = sm::test::get_port_words(tb->m_agg, agg_bits);
    const Frame& f = frames[static_cast<size_t>(o->frame)];
    std::string what;  // one check per pixel, the first wrong level reported
    for (int d = 0; d < kDisp && what.empty(); ++d) {
      const uint32_t g = get_field(got, d * cw, cw);
      const uint32_t e = f.expect.at(o->x, o->y, d);
      if (g != e) what = fmt::format("level {}: expected {}, got {}", d, e, g);
    }
    t.check(what.empty(), [&] { return fmt::format("frame {} x {} y {} {}", o->frame, o->x, o->y, what); });
  }
  t.all_out();
  return t.finish(fmt::format("sm_sw_aggregate MAX_WIDTH={} DISP={} CENSUS={} SW={} COST_SHIFT={} PU={} width={}",
                              kMaxWidth, kDisp, kCensus, kSw, kCostShift, kDisp / kFold, width));
}
