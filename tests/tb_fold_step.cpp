// Direct test of sm_fold_step (the sub-step counter of sm_dp, sm_wta and sm_right_wta),
// against its definition counted another way: a start edge is a clock with ce high or
// rst_n low, and the k-th clock after the last start (k = 0 the first) runs a sub-step
// when k < F, numbered k (counting up) or F-1-k (DOWN). Random ce gaps of at least F
// clocks from a fixed seed, the first ce F or more clocks after reset, resets in the
// middle of a run, and gaps of exactly F (no idle clock between beats).
#include <fmt/format.h>

#include <cstdint>
#include <random>

#include SM_VTOP_H
#include "sm_block_test.hpp"

namespace {
constexpr int kF = SM_P_F;
#ifdef SM_P_DOWN
constexpr bool kDown = SM_P_DOWN != 0;
#else
constexpr bool kDown = false;
#endif
}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_fold_step direct test"};
  uint32_t seed = 1;
  int clocks = 20000;
  t.option("--seed", seed, "stimulus seed");
  t.option("--clocks", clocks, "clocks to run").range(1, 1 << 24);
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(seed);

  long since = 0;  // clocks since the last start edge
  int gap = kF;    // clocks left until a ce is allowed
  long runs = 0, tight = 0, resets = 0;
  for (int c = 0; c < clocks; ++c) {
    const bool rst = c < 3 || rng() % 2000 == 0;  // reset at the start, and now and then
    bool ce = false;
    if (!rst && gap <= 0) ce = rng() % 4 == 0 || rng() % 8 == 0;
    t->rst_n = rst ? 0 : 1;
    t->ce = ce ? 1 : 0;
    t->eval();
    // before the edge: the outputs describe this clock's edge
    const bool start = rst || ce;
    const bool run = since < kF;
    const int g = kDown ? kF - 1 - static_cast<int>(since) : static_cast<int>(since);
    // the registers hold nothing defined before the first reset edge
    const bool defined = c > 0;
    t.check(t->m_start == start && t->m_step == (t->m_run && !start) &&
                (!defined || (t->m_run == run && (!run || t->m_g == g))),
            [&] {
              return fmt::format(
                  "clock {} (rst {} ce {}, {} clocks after a start): start {} run {} step {} g {}, want "
                  "start {} run {} g {}",
                  c, rst, ce, since, t->m_start, t->m_run, t->m_step, t->m_g, start, run, g);
            });
    runs += run;
    tight += ce && since == kF;
    resets += rst && c >= 3;
    t.tick();
    since = start ? 0 : since + 1;
    gap = start ? kF : gap - 1;
  }
  t.check(tight > 0 && resets > 0 && runs > 0, [&] {
    return fmt::format("stimulus missed a case: {} beats with no idle clock, {} resets mid-run", tight, resets);
  });
  return t.finish(fmt::format("tb_fold_step F={} DOWN={} clocks={}: {} sub-steps, {} back-to-back beats, {} resets", kF,
                              kDown, clocks, runs, tight, resets));
}
