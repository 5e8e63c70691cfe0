// Block test of sm_census against the model's census_transform: random images, frames
// of different heights back to back, an odd width, virtual flush rows and ce gaps with
// garbage on every beat the block must ignore. Every real output pixel is compared.
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
#ifndef SM_TB_WIDTH
#define SM_TB_WIDTH 37
#endif
#ifndef SM_TB_H0
#define SM_TB_H0 13
#endif

std::string hex(const sm::CensusVec& v) { return fmt::format("{:016x}{:016x}{:016x}{:016x}", v[3], v[2], v[1], v[0]); }

sm::Image8 random_image(int w, int h, std::mt19937& rng) {
  sm::Image8 im(w, h);
  // a few grey levels so equal neighbours (bit 0) are frequent too
  for (auto& p : im.px) p = static_cast<uint8_t>((rng() % 3 == 0) ? (rng() & 3) * 64 : rng());
  return im;
}

}  // namespace

int main() {
  const int w = SM_TB_WIDTH;
  static_assert(kMaxWidth >= SM_TB_WIDTH, "test width above MAX_WIDTH");
  const int r = (kCensus - 1) / 2;
  const std::vector<int> heights = {SM_TB_H0, 2, 7};  // H = 2 is shorter than the window
  sm::HwConfig hw;
  hw.max_width = kMaxWidth;
  hw.census = kCensus;
  const int cb = hw.census_bits();

  std::mt19937 rng(1234);
  std::vector<sm::Image8> left, right;
  std::vector<sm::CensusImage> cl, cr;
  for (int h : heights) {
    left.push_back(random_image(w, h, rng));
    right.push_back(random_image(w, h, rng));
    cl.push_back(sm::census_transform(left.back(), hw));
    cr.push_back(sm::census_transform(right.back(), hw));
  }
  const auto sched = sm::test::make_schedule(w, heights, r + 2);

  sm::Testbench<SM_VTOP> tb;
  sm::CoverageOnExit cov{tb->contextp()};
  sm::test::CeGen ce_gen(0xce11u, 30);
  sm::test::OutputOrder order(w, heights);
  tb->width = w;
  tb->ce = 1;
  tb->s_side = 0;
  tb->rst_n = 0;
  for (int i = 0; i < 3; ++i) tb.tick();
  tb->rst_n = 1;

  long passed = 0, failed = 0;
  uint8_t last_side = 0;
  for (size_t n = 0; n < sched.size();) {
    const bool ce = ce_gen.next();
    tb->ce = ce;
    if (ce && sched[n].frame >= 0) {
      const auto& b = sched[n];
      tb->s_side = b.side;
      tb->s_left = left[b.frame].at(b.x, b.y);
      tb->s_right = right[b.frame].at(b.x, b.y);
    } else {
      // virtual beat (its sideband is real) or an idle cycle (all garbage)
      tb->s_side = ce ? sched[n].side : static_cast<uint8_t>(rng() & 31);
      tb->s_left = static_cast<uint8_t>(rng());
      tb->s_right = static_cast<uint8_t>(rng());
    }
    tb.tick();
    if (!ce) {
      if (tb->m_side != last_side) {
        fmt::print("FAIL: m_side changed without ce\n");
        ++failed;
      }
      continue;
    }
    ++n;
    last_side = tb->m_side;
    if (!(tb->m_side & sm::test::kReal)) continue;
    sm::test::BeatInfo p;
    try {
      p = order.next(tb->m_side);
    } catch (const std::exception& e) {
      fmt::print("FAIL: {}\n", e.what());
      ++failed;
      break;
    }
    const auto gl = sm::test::get_port_u64<4>(tb->m_cl, cb);
    const auto gr = sm::test::get_port_u64<4>(tb->m_cr, cb);
    const auto& el = cl[p.frame].at(p.x, p.y);
    const auto& er = cr[p.frame].at(p.x, p.y);
    const int eleft = left[p.frame].at(p.x, p.y);
    if (gl != el || gr != er || tb->m_left != eleft) {
      if (failed == 0)
        fmt::print(
            "FIRST MISMATCH frame {} x {} y {}:\n  cl expected {} got {}\n  cr expected {} "
            "got {}\n  left expected {} got {}\n",
            p.frame, p.x, p.y, hex(el), hex(gl), hex(er), hex(gr), eleft, tb->m_left);
      ++failed;
    } else {
      ++passed;
    }
  }
  if (!order.done()) {
    fmt::print("FAIL: not every pixel came out\n");
    ++failed;
  }
  fmt::print("tb_census MAX_WIDTH={} CENSUS={} W={}: {} passed, {} failed\n", kMaxWidth, kCensus, w, passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
