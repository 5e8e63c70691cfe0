// Block test of sm_cost against the model's hamming_cost. The census inputs come from
// the model's census images of random image pairs (the right image a shifted copy of
// the left with noise, so low costs occur); virtual beats and idle cycles carry
// garbage. Every level of every real output pixel is compared. Folded (SM_P_PU defined,
// F = DISP / PU > 1): ce comes at most once every F clocks and the next beat's input
// (real or garbage) is held from the clock after a ce until its own ce, as sm_top
// guarantees; at F = 1 idle clocks carry garbage.
#include <fmt/format.h>

#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "beat_schedule.hpp"
#include "census.hpp"
#include "sm_port.hpp"
#include "sm_tb.hpp"
#include "sm_coverage.hpp"

namespace {

constexpr int kMaxWidth = SM_P_MAX_WIDTH;
constexpr int kCensus = SM_P_CENSUS;
constexpr int kDisp = SM_P_DISP;
#ifdef SM_P_PU
constexpr int kPu = SM_P_PU;
#else
constexpr int kPu = kDisp;
#endif
static_assert(kDisp % kPu == 0, "PU must divide DISP");
constexpr int kFold = kDisp / kPu;  // clocks per beat
#ifndef SM_TB_WIDTH
#define SM_TB_WIDTH 37
#endif
#ifndef SM_TB_H0
#define SM_TB_H0 9
#endif

sm::CensusVec garbage(std::mt19937& rng) {
  auto w = [&] { return (static_cast<uint64_t>(rng()) << 32) | rng(); };
  return {w(), w(), w(), w()};
}

}  // namespace

int main() {
  const int w = SM_TB_WIDTH;
  static_assert(kMaxWidth >= SM_TB_WIDTH, "test width above MAX_WIDTH");
  const std::vector<int> heights = {SM_TB_H0, 3, 5};
  sm::HwConfig hw;
  hw.max_width = kMaxWidth;
  hw.census = kCensus;
  hw.disp = kDisp;
  const int cb = hw.census_bits();
  int hwb = 0;  // HW = clog2(CB + 1)
  while ((1 << hwb) < cb + 1) ++hwb;

  std::mt19937 rng(4321);
  std::vector<sm::Image8> left;
  std::vector<sm::CensusImage> cl, cr;
  std::vector<sm::CostVolume> cost;
  for (size_t f = 0; f < heights.size(); ++f) {
    const int h = heights[f];
    const int shift = static_cast<int>(3 + 5 * f) % kDisp;
    sm::Image8 l(w, h), r(w, h);
    for (auto& p : l.px) p = static_cast<uint8_t>(rng());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        r.at(x, y) = (x + shift < w && rng() % 8) ? l.at(x + shift, y) : static_cast<uint8_t>(rng());
    left.push_back(l);
    cl.push_back(sm::census_transform(l, hw));
    cr.push_back(sm::census_transform(r, hw));
    cost.push_back(sm::hamming_cost(cl.back(), cr.back(), hw));
  }
  const auto sched = sm::test::make_schedule(w, heights, 1);

  sm::Testbench<SM_VTOP> tb;
  sm::CoverageOnExit cov{tb->contextp()};
  sm::test::CeGen ce_gen(0xc057u, 30, kFold);
  sm::test::OutputOrder order(w, heights);
  tb->width = w;
  tb->ce = 1;
  tb->s_side = 0;
  tb->rst_n = 0;
  for (int i = 0; i < 3; ++i) tb.tick();
  tb->rst_n = 1;

  long passed = 0, failed = 0;
  // Folded: the inputs of beat n, drawn once and held on every clock up to its ce.
  size_t held = sched.size();
  uint8_t held_side = 0, held_left = 0;
  sm::CensusVec held_cl{}, held_cr{};
  int warm = kFold - 1;
  for (size_t n = 0; n < sched.size();) {
    // Folded: the reset starts the sub-steps of the first beat like a ce; its ce comes
    // F clocks later at the earliest.
    const bool ce = warm > 0 ? (--warm, false) : ce_gen.next();
    tb->ce = ce;
    if (kFold > 1) {
      if (held != n) {
        const auto& b = sched[n];
        held = n;
        held_side = b.side;
        if (b.frame >= 0) {
          held_cl = cl[b.frame].at(b.x, b.y);
          held_cr = cr[b.frame].at(b.x, b.y);
          held_left = left[b.frame].at(b.x, b.y);
        } else {
          held_cl = garbage(rng);
          held_cr = garbage(rng);
          held_left = static_cast<uint8_t>(rng());
        }
      }
      tb->s_side = held_side;
      sm::test::set_port_u64(tb->s_cl, held_cl, cb);
      sm::test::set_port_u64(tb->s_cr, held_cr, cb);
      tb->s_left = held_left;
    } else if (ce && sched[n].frame >= 0) {
      const auto& b = sched[n];
      tb->s_side = b.side;
      sm::test::set_port_u64(tb->s_cl, cl[b.frame].at(b.x, b.y), cb);
      sm::test::set_port_u64(tb->s_cr, cr[b.frame].at(b.x, b.y), cb);
      tb->s_left = left[b.frame].at(b.x, b.y);
    } else {
      tb->s_side = ce ? sched[n].side : static_cast<uint8_t>(rng() & 31);
      sm::test::set_port_u64(tb->s_cl, garbage(rng), cb);
      sm::test::set_port_u64(tb->s_cr, garbage(rng), cb);
      tb->s_left = static_cast<uint8_t>(rng());
    }
    tb.tick();
    if (!ce) continue;
    ++n;
    if (!(tb->m_side & sm::test::kReal)) continue;
    sm::test::BeatInfo p;
    try {
      p = order.next(tb->m_side);
    } catch (const std::exception& e) {
      fmt::print("FAIL: {}\n", e.what());
      ++failed;
      break;
    }
    bool ok = tb->m_left == left[p.frame].at(p.x, p.y);
    if (!ok && failed == 0)
      fmt::print("FIRST MISMATCH frame {} x {} y {}: left expected {} got {}\n", p.frame, p.x, p.y,
                 left[p.frame].at(p.x, p.y), tb->m_left);
    for (int d = 0; d < kDisp && ok; ++d) {
      const unsigned got = sm::test::plane_bits(tb->m_cost, d, hwb, kDisp);
      const unsigned exp = cost[p.frame].at(p.x, p.y, d);
      if (got != exp) {
        if (failed == 0)
          fmt::print("FIRST MISMATCH frame {} x {} y {} d {}: expected {} got {}\n", p.frame, p.x, p.y, d, exp, got);
        ok = false;
      }
    }
    if (ok)
      ++passed;
    else
      ++failed;
  }
  if (!order.done()) {
    fmt::print("FAIL: not every pixel came out\n");
    ++failed;
  }
  fmt::print("tb_cost MAX_WIDTH={} CENSUS={} DISP={} PU={} W={}: {} passed, {} failed\n", kMaxWidth, kCensus, kDisp,
             kPu, w, passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
